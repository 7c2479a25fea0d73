// Our legacy .vtk reader against VTK's own: the same polydata from what VTK's writer writes (ASCII
// and BINARY, file versions 4.2 and 5.1, many value types, attributes and field data) and from the
// real atlas surfaces; and on every cut-short or byte-damaged copy, a problem or a consistent
// polydata, never a crash.
#include "Core/Testing/FreshTempDir.h"
#include "IO/LegacyVtkReader.h"

#include <gtest/gtest.h>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkPolyDataWriter.h>
#include <vtkShortArray.h>
#include <vtkUnsignedCharArray.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <unistd.h>

namespace fs = std::filesystem;
using colonmap::io::ReadLegacyPolyData;

namespace {

fs::path TempDir(const std::string& name) { return colonmap::FreshTempDir("legacy", name); }

// Points, one vertex, one line, a triangle and a quad; point, cell and field arrays of several types.
vtkSmartPointer<vtkPolyData> Sample() {
  auto data = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  for (int i = 0; i < 6; ++i) points->InsertNextPoint(0.5 * i, -1.25 * i, i * i / 3.0);
  data->SetPoints(points);
  vtkNew<vtkCellArray> verts, lines, polys;
  const vtkIdType v[1] = {5}, l[3] = {0, 4, 5}, t[3] = {0, 1, 2}, q[4] = {1, 2, 3, 4};
  verts->InsertNextCell(1, v);
  lines->InsertNextCell(3, l);
  polys->InsertNextCell(3, t);
  polys->InsertNextCell(4, q);
  data->SetVerts(verts);
  data->SetLines(lines);
  data->SetPolys(polys);
  vtkNew<vtkFloatArray> scalars;
  scalars->SetName("Mean Curvature");  // a space: written percent-encoded
  vtkNew<vtkDoubleArray> vectors;
  vectors->SetName("Flow");
  vectors->SetNumberOfComponents(3);
  vtkNew<vtkShortArray> ids;
  ids->SetName("SegmentId");
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName("Colours");
  colours->SetNumberOfComponents(4);
  for (int i = 0; i < 6; ++i) {
    scalars->InsertNextValue(0.1f * i - 0.3f);
    vectors->InsertNextTuple3(i, -i, 1e-7 * i);
    ids->InsertNextValue(static_cast<short>(i % 5 - 2));
    colours->InsertNextTuple4(i, 255 - i, 7, 128);
  }
  data->GetPointData()->SetScalars(scalars);
  data->GetPointData()->SetVectors(vectors);
  data->GetPointData()->AddArray(ids);
  data->GetPointData()->AddArray(colours);
  vtkNew<vtkIntArray> cellIds;
  cellIds->SetName("CellId");
  vtkNew<vtkDoubleArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  for (int c = 0; c < 4; ++c) {
    cellIds->InsertNextValue(100 * c - 7);
    normals->InsertNextTuple3(0, 0, c % 2 ? 1 : -1);
  }
  data->GetCellData()->SetScalars(cellIds);
  data->GetCellData()->SetNormals(normals);
  vtkNew<vtkDoubleArray> field;
  field->SetName("ProneV");
  field->SetNumberOfComponents(3);
  for (int i = 0; i < 5; ++i) field->InsertNextTuple3(i, 2 * i, 3.5 * i);
  data->GetFieldData()->AddArray(field);
  return data;
}

std::string Cells(vtkCellArray* cells) {
  std::string s;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < cells->GetNumberOfCells(); ++c) {
    cells->GetCellAtId(c, ids);
    s += "[";
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) s += std::to_string(ids->GetId(k)) + " ";
    s += "]";
  }
  return s;
}

void ExpectSameArrays(vtkFieldData* a, vtkFieldData* b, const std::string& what) {
  int numeric = 0;
  for (int i = 0; i < a->GetNumberOfArrays(); ++i) {
    vtkDataArray* x = a->GetArray(i);
    if (!x) continue;
    ++numeric;
    vtkDataArray* y = b->GetArray(x->GetName());
    ASSERT_NE(y, nullptr) << what << ": array " << x->GetName();
    EXPECT_EQ(x->GetNumberOfComponents(), y->GetNumberOfComponents()) << what << " " << x->GetName();
    ASSERT_EQ(x->GetNumberOfTuples(), y->GetNumberOfTuples()) << what << " " << x->GetName();
    for (vtkIdType t = 0; t < x->GetNumberOfTuples(); ++t)
      for (int c = 0; c < x->GetNumberOfComponents(); ++c)
        EXPECT_EQ(x->GetComponent(t, c), y->GetComponent(t, c)) << what << " " << x->GetName() << " " << t;
  }
  int numericB = 0;
  for (int i = 0; i < b->GetNumberOfArrays(); ++i) numericB += b->GetArray(i) != nullptr;
  EXPECT_EQ(numeric, numericB) << what;
}

// Ours and VTK's reading of one file are the same polydata.
void ExpectSameAsVtk(const std::string& path) {
  vtkNew<vtkPolyDataReader> vtk;
  vtk->SetFileName(path.c_str());
  vtk->Update();
  vtkPolyData* expected = vtk->GetOutput();
  vtkNew<vtkPolyData> ours;
  ASSERT_EQ(ReadLegacyPolyData(path, ours), "") << path;
  ASSERT_EQ(ours->GetNumberOfPoints(), expected->GetNumberOfPoints()) << path;
  for (vtkIdType i = 0; i < expected->GetNumberOfPoints(); ++i) {
    double p[3], r[3];
    expected->GetPoint(i, p);
    ours->GetPoint(i, r);
    EXPECT_EQ(p[0], r[0]);
    EXPECT_EQ(p[1], r[1]);
    EXPECT_EQ(p[2], r[2]);
  }
  EXPECT_EQ(Cells(ours->GetVerts()), Cells(expected->GetVerts())) << path;
  EXPECT_EQ(Cells(ours->GetLines()), Cells(expected->GetLines())) << path;
  EXPECT_EQ(Cells(ours->GetPolys()), Cells(expected->GetPolys())) << path;
  EXPECT_EQ(Cells(ours->GetStrips()), Cells(expected->GetStrips())) << path;
  ExpectSameArrays(expected->GetPointData(), ours->GetPointData(), path + " point data");
  ExpectSameArrays(expected->GetCellData(), ours->GetCellData(), path + " cell data");
  ExpectSameArrays(expected->GetFieldData(), ours->GetFieldData(), path + " field data");
}

std::string Write(vtkPolyData* data, const fs::path& path, bool binary, int version) {
  vtkNew<vtkPolyDataWriter> w;
  w->SetFileName(path.string().c_str());
  w->SetInputData(data);
  if (binary) w->SetFileTypeToBinary();
  else w->SetFileTypeToASCII();
  w->SetFileVersion(version);
  EXPECT_EQ(w->Write(), 1);
  return path.string();
}

std::string Bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A polydata as read must be whole: cell ids among the points, arrays of the declared size.
void ExpectConsistent(vtkPolyData* data, const std::string& what) {
  const vtkIdType n = data->GetNumberOfPoints();
  ASSERT_GT(n, -1);
  for (vtkCellArray* cells : {data->GetVerts(), data->GetLines(), data->GetPolys(), data->GetStrips()}) {
    vtkNew<vtkIdList> ids;
    for (vtkIdType c = 0; c < cells->GetNumberOfCells(); ++c) {
      cells->GetCellAtId(c, ids);
      for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) {
        EXPECT_GE(ids->GetId(k), 0) << what;
        EXPECT_LT(ids->GetId(k), n) << what;
      }
    }
  }
  for (int i = 0; i < data->GetPointData()->GetNumberOfArrays(); ++i)
    EXPECT_EQ(data->GetPointData()->GetArray(i)->GetNumberOfTuples(), n) << what;
}

}  // namespace

TEST(LegacyVtkReader, ReadsWhatVtkWritesAsVtkReadsIt) {
  const fs::path dir = TempDir("written");
  vtkSmartPointer<vtkPolyData> data = Sample();
  for (const bool binary : {false, true})
    for (const int version : {vtkPolyDataWriter::VTK_LEGACY_READER_VERSION_4_2, vtkPolyDataWriter::VTK_LEGACY_READER_VERSION_5_1}) {
      const std::string path =
          Write(data, dir / ("s" + std::to_string(version) + (binary ? "b" : "a") + ".vtk"), binary, version);
      ExpectSameAsVtk(path);
      vtkNew<vtkPolyData> ours;
      ASSERT_EQ(ReadLegacyPolyData(path, ours), "");
      ASSERT_NE(ours->GetPointData()->GetArray("Mean Curvature"), nullptr) << "percent-decoded name";
      EXPECT_FLOAT_EQ(static_cast<float>(ours->GetPointData()->GetArray("Mean Curvature")->GetComponent(1, 0)), -0.2f);
      EXPECT_EQ(ours->GetCellData()->GetArray("CellId")->GetComponent(3, 0), 293);
      EXPECT_EQ(ours->GetFieldData()->GetArray("ProneV")->GetNumberOfTuples(), 5);
      EXPECT_EQ(Cells(ours->GetPolys()), "[0 1 2 ][1 2 3 4 ]");
    }
  fs::remove_all(dir);
}

TEST(LegacyVtkReader, ReadsTheAtlasSurfacesAsVtkDoes) {
  int files = 0;
  for (const char* atlas : {"gca-00020", "hubmap-vhm-00070", "hubmap-vhf-00080"})
    for (const auto& entry : fs::directory_iterator(fs::path(COLONMAP_SHARED_DIR) / "data" / atlas / "SegmentedSurfaces"))
      if (entry.path().extension() == ".vtk") {
        ExpectSameAsVtk(entry.path().string());
        ++files;
      }
  EXPECT_GE(files, 10);
}

// Every prefix of a small file, ASCII and BINARY, both layouts, and random byte damage: a problem
// or a whole polydata, and no crash (the suite runs under ASan too).
TEST(LegacyVtkReader, CutOrDamagedFilesGiveAProblemOrAWholePolyData) {
  const fs::path dir = TempDir("damaged");
  vtkSmartPointer<vtkPolyData> data = Sample();
  std::mt19937 random(7);
  int refused = 0, read = 0;
  for (const bool binary : {false, true})
    for (const int version : {vtkPolyDataWriter::VTK_LEGACY_READER_VERSION_4_2, vtkPolyDataWriter::VTK_LEGACY_READER_VERSION_5_1}) {
      const std::string bytes = Bytes(Write(data, dir / "whole.vtk", binary, version));
      const fs::path damaged = dir / "damaged.vtk";
      const auto check = [&](const std::string& content, const std::string& what) {
        std::ofstream(damaged, std::ios::binary) << content;
        vtkNew<vtkPolyData> out;
        const std::string problem = ReadLegacyPolyData(damaged.string(), out);
        if (problem.empty()) {
          ++read;
          ExpectConsistent(out, what);
        } else {
          ++refused;
          EXPECT_EQ(problem.find('\n'), std::string::npos) << what << ": " << problem;
        }
      };
      for (std::size_t cut = 0; cut < bytes.size(); ++cut) check(bytes.substr(0, cut), "cut at " + std::to_string(cut));
      for (int trial = 0; trial < 300; ++trial) {
        std::string copy = bytes;
        for (int k = 0; k < 3; ++k)
          copy[random() % copy.size()] = static_cast<char>(random() % 256);
        check(copy, "damaged, trial " + std::to_string(trial));
      }
    }
  EXPECT_GT(refused, 1000);  // most cuts end inside a section
  EXPECT_GT(read, 0);        // some damage leaves a readable file (a changed value)
  fs::remove_all(dir);
}

TEST(LegacyVtkReader, NamesTheProblem) {
  const fs::path dir = TempDir("problems");
  const auto problemOf = [&](const std::string& content) {
    std::ofstream(dir / "p.vtk", std::ios::binary) << content;
    vtkNew<vtkPolyData> out;
    return ReadLegacyPolyData((dir / "p.vtk").string(), out);
  };
  const std::string head = "# vtk DataFile Version 3.0\ntitle\nASCII\nDATASET POLYDATA\n";
  EXPECT_EQ(problemOf(head + "POINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 1 4\n3 0 1 2\n"), "");
  EXPECT_NE(problemOf("hello\n").find("not a legacy VTK file"), std::string::npos);
  EXPECT_NE(problemOf("# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\n").find("not polydata"),
            std::string::npos);
  EXPECT_NE(problemOf(head + "POINTS 1000000000000 float\n0 0 0\n").find("cut short"), std::string::npos);
  EXPECT_NE(problemOf(head + "POINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 1 4\n3 0 1 7\n").find("naming point 7"),
            std::string::npos);
  EXPECT_NE(problemOf(head + "POINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 1 4\n9 0 1 2\n").find("more than its list"),
            std::string::npos);
  EXPECT_NE(problemOf(head + "POINTS 3 float\n0 0 x 1 0 0 0 1 0\n").find("'x'"), std::string::npos);
  EXPECT_NE(problemOf(head + "POINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOINT_DATA 4\n").find("there are 3 points"),
            std::string::npos);
  EXPECT_NE(problemOf(head + "POINTS 3 float\n0 0 0 1 0 0 0 1 0\nBANANAS 3\n").find("unknown keyword 'BANANAS'"),
            std::string::npos);
  EXPECT_NE(problemOf(head + "POINTS 3 bit\n0 0 0 1 0 0 0 1 0\n").find("not read"), std::string::npos);
  EXPECT_NE(problemOf(head + "POLYGONS 1 4\n3 0 1 2\n").find("before its POINTS"), std::string::npos);
  fs::remove_all(dir);
}
