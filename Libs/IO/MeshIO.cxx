#include "IO/MeshIO.h"
#include "IO/FileNames.h"
#include "IO/LegacyVtkReader.h"
#include "IO/XmlPolyDataCheck.h"

#include "Core/Error.h"

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataWriter.h>
#include <vtkSTLReader.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <vector>

namespace fs = std::filesystem;

namespace colonmap::io {
namespace {

// Collects VTK errors of one reader/writer instead of letting them reach stderr (observers are
// per object: no global state is touched).
struct ErrorCollector {
  std::string message;
  vtkNew<vtkCallbackCommand> command;
  explicit ErrorCollector(vtkObject* object) {
    command->SetClientData(this);
    command->SetCallback([](vtkObject*, unsigned long event, void* client, void* data) {
      auto* self = static_cast<ErrorCollector*>(client);
      if (event == vtkCommand::ErrorEvent && self->message.empty() && data) {
        self->message = static_cast<const char*>(data);
        // "ERROR: In <source file>, line N\n<class> (0x..): <what went wrong>": the user needs the last part.
        if (const std::size_t at = self->message.find("): "); at != std::string::npos) self->message.erase(0, at + 3);
        for (auto& c : self->message) if (c == '\n') c = ' ';
        while (!self->message.empty() && self->message.back() == ' ') self->message.pop_back();
      }
    });
    object->AddObserver(vtkCommand::ErrorEvent, command);
    object->AddObserver(vtkCommand::WarningEvent, command);
  }
};


// VTK's own log (a parser's errors, with terminal colours, 10-49 lines) must not reach the user's
// stderr before our one line (issue 24): what a reader reports reaches us through the
// ErrorCollector's events and becomes that line; the rest goes nowhere.
void QuietVtkLog() {
  static const bool once = [] {
    vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
    return true;
  }();
  (void)once;
}

vtkSmartPointer<vtkPolyData> ReadPolyData(const std::string& path, const std::string& what) {
  QuietVtkLog();
  std::error_code ec;
  if (path.empty()) throw Error(what + ": no file given");
  if (!fs::exists(path, ec)) throw InputError(what, path, "file does not exist");
  if (fs::is_directory(path, ec)) throw InputError(what, path, "is a folder, not a surface file");
  const std::string ext = LowerCase(fs::path(path).extension().string());
  vtkSmartPointer<vtkPolyData> output;
  std::string error;
  if (ext == ".vtp") {
    if (const std::string problem = CheckXmlPolyData(path); !problem.empty()) throw InputError(what, path, problem);
    vtkNew<vtkXMLPolyDataReader> r;
    ErrorCollector errors(r);
    r->SetFileName(path.c_str());
    r->Update();
    error = errors.message;
    if (error.empty() && r->GetErrorCode() != 0) error = "read error";
    output = r->GetOutput();
  } else if (ext == ".vtk") {
    // Our own reader: VTK's trusts every count of a legacy file (LegacyVtkReader.h).
    output = vtkSmartPointer<vtkPolyData>::New();
    if (const std::string problem = ReadLegacyPolyData(path, output); !problem.empty())
      throw InputError(what, path, problem);
  } else if (ext == ".stl") {
    vtkNew<vtkSTLReader> r;
    ErrorCollector errors(r);
    r->SetFileName(path.c_str());
    r->Update();
    error = errors.message;
    output = r->GetOutput();
  } else {
    throw InputError(what, path, "unknown surface format (expected .vtp, .vtk or .stl)");
  }
  if (error.find("No Points element") != std::string::npos) throw InputError(what, path, "holds no points");
  if (!error.empty()) throw InputError(what, path, "cannot be read (" + error + ")");
  if (!output || output->GetNumberOfPoints() == 0) throw InputError(what, path, "holds no points");
  return output;
}

void ReadArrays(vtkDataSetAttributes* attributes, std::map<std::string, DataArray>& arrays, vtkIdType n) {
  for (int a = 0; a < attributes->GetNumberOfArrays(); ++a) {
    vtkDataArray* array = attributes->GetArray(a);
    if (!array || !array->GetName() || array->GetNumberOfTuples() != n) continue;
    DataArray d;
    d.integer = array->GetDataType() != VTK_FLOAT && array->GetDataType() != VTK_DOUBLE;
    const int k = array->GetNumberOfComponents();
    d.values.resize(n, k);
    for (vtkIdType i = 0; i < n; ++i)
      for (int c = 0; c < k; ++c) d.values(i, c) = array->GetComponent(i, c);
    arrays[array->GetName()] = std::move(d);
  }
}

void WriteArrays(const std::map<std::string, DataArray>& arrays, vtkFieldData* attributes) {
  for (const auto& [name, d] : arrays) {
    vtkSmartPointer<vtkDataArray> array;
    if (d.integer) array = vtkSmartPointer<vtkIntArray>::New();
    else array = vtkSmartPointer<vtkDoubleArray>::New();
    array->SetName(name.c_str());
    array->SetNumberOfComponents(static_cast<int>(d.values.cols()));
    array->SetNumberOfTuples(d.values.rows());
    for (Eigen::Index i = 0; i < d.values.rows(); ++i)
      for (Eigen::Index c = 0; c < d.values.cols(); ++c)
        array->SetComponent(i, static_cast<int>(c), d.values(i, c));
    attributes->AddArray(array);
  }
}

// Field data: each array keeps its own number of tuples.
void ReadFieldArrays(vtkFieldData* field, FieldArrays& arrays) {
  if (!field) return;
  for (int a = 0; a < field->GetNumberOfArrays(); ++a) {
    vtkDataArray* array = field->GetArray(a);  // null for string arrays
    if (!array || !array->GetName()) continue;
    DataArray d;
    d.integer = array->GetDataType() != VTK_FLOAT && array->GetDataType() != VTK_DOUBLE;
    const vtkIdType n = array->GetNumberOfTuples();
    const int k = array->GetNumberOfComponents();
    d.values.resize(n, k);
    for (vtkIdType i = 0; i < n; ++i)
      for (int c = 0; c < k; ++c) d.values(i, c) = array->GetComponent(i, c);
    arrays[array->GetName()] = std::move(d);
  }
}

vtkSmartPointer<vtkPoints> ToPoints(const Eigen::MatrixXd& V) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(V.rows());
  for (Eigen::Index i = 0; i < V.rows(); ++i) points->SetPoint(i, V(i, 0), V(i, 1), V(i, 2));
  return points;
}

Eigen::MatrixXd FromPoints(vtkPoints* points) {
  Eigen::MatrixXd V(points->GetNumberOfPoints(), 3);
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i) {
    double p[3];
    points->GetPoint(i, p);
    V.row(i) << p[0], p[1], p[2];
  }
  return V;
}

void WritePolyData(vtkPolyData* data, const std::string& path, const std::string& what) {
  QuietVtkLog();
  const std::string ext = LowerCase(fs::path(path).extension().string());
  std::string error;
  int ok = 0;
  if (ext == ".vtp") {
    vtkNew<vtkXMLPolyDataWriter> w;
    ErrorCollector errors(w);
    w->SetFileName(path.c_str());
    w->SetInputData(data);
    w->SetDataModeToAppended();
    // Raw, not zlib: the registration's two files (about 80 MB of mostly incompressible doubles)
    // took 2.9 s to compress at VTK's default level, 2.6 s at level 1, and shrank only by a
    // quarter. Every VTK reader reads it (old Slicer included).
    w->SetCompressorTypeToNone();
    w->EncodeAppendedDataOff();
    ok = w->Write();
    error = errors.message;
  } else if (ext == ".vtk") {
    vtkNew<vtkPolyDataWriter> w;
    ErrorCollector errors(w);
    w->SetFileName(path.c_str());
    w->SetInputData(data);
    w->SetFileTypeToBinary();
    ok = w->Write();
    error = errors.message;
  } else {
    throw InputError(what, path, "unknown surface format (expected .vtp or .vtk)");
  }
  if (!ok || !error.empty()) throw InputError(what, path, "cannot be written (" + error + ")");
}

}  // namespace

namespace {

// What a reader checks at the door (issue 24): NaN or infinite coordinates make later stages
// crash or spin (a centroid of NaNs, a locator that never converges), and a triangle naming a
// point past the end reads memory that is not ours. NaN in a data array is refused too; +-inf is
// allowed there (a dilatation K of a degenerate face is +inf by definition).
void CheckFinitePoints(const Eigen::MatrixXd& V, const std::string& path, const std::string& what) {
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    if (!V.row(i).allFinite())
      throw InputError(what, path, "point " + std::to_string(i) + " has a NaN or infinite coordinate");
}

// A cell list as read, before it is walked (found by fuzzing): offsets that decrease made VTK's
// traversal read before the start of the connectivity, and a point id of 2^32 became point 0 when
// cast to int. Ids are checked here, as 64-bit numbers.
void CheckCells(vtkCellArray* cells, vtkIdType points, const std::string& kind, const std::string& path,
                const std::string& what) {
  if (points > std::numeric_limits<int>::max())
    throw InputError(what, path, "has " + std::to_string(points) + " points, more than we can index");
  if (!cells->IsValid())
    throw InputError(what, path, "has " + kind + " offsets that decrease or do not match the connectivity");
  vtkNew<vtkIdList> ids;
  for (vtkIdType cell = 0; cell < cells->GetNumberOfCells(); ++cell) {
    cells->GetCellAtId(cell, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      if (ids->GetId(k) < 0 || ids->GetId(k) >= points)
        throw InputError(what, path, kind + " " + std::to_string(cell) + " names point " + std::to_string(ids->GetId(k)) +
                                         ", but there are " + std::to_string(points) + " points");
  }
}

}  // namespace

void CheckMesh(const TriangleMesh& mesh, const std::string& path, const std::string& what) {
  CheckFinitePoints(mesh.V, path, what);
  const Eigen::Index n = mesh.V.rows();
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (mesh.F(f, k) < 0 || mesh.F(f, k) >= n)
        throw InputError(what, path, "triangle " + std::to_string(f) + " names point " + std::to_string(mesh.F(f, k)) +
                                         ", but there are " + std::to_string(n) + " points");
  for (const auto* arrays : {&mesh.pointData, &mesh.cellData})
    for (const auto& [name, d] : *arrays)
      if (d.values.array().isNaN().any())
        throw InputError(what, path, "array " + name + " holds NaN values");
}

TriangleMesh ReadMesh(const std::string& path, const std::string& what) { return ReadMesh(path, what, nullptr); }

TriangleMesh ReadMesh(const std::string& path, const std::string& what, FieldArrays* fieldData) {
  vtkSmartPointer<vtkPolyData> data = ReadPolyData(path, what);
  TriangleMesh mesh;
  mesh.V = FromPoints(data->GetPoints());
  // Fan-triangulate polygons (strips are rare in our inputs and are not accepted).
  if (data->GetNumberOfStrips() > 0) throw InputError(what, path, "triangle strips are not supported");
  std::vector<Eigen::Vector3i> faces;
  std::vector<vtkIdType> faceSource;
  vtkCellArray* polys = data->GetPolys();
  CheckCells(polys, data->GetNumberOfPoints(), "polygon", path, what);
  vtkNew<vtkIdList> ids;
  polys->InitTraversal();
  for (vtkIdType cell = 0; polys->GetNextCell(ids); ++cell) {
    for (vtkIdType k = 1; k + 1 < ids->GetNumberOfIds(); ++k) {
      faces.emplace_back(static_cast<int>(ids->GetId(0)), static_cast<int>(ids->GetId(k)),
                         static_cast<int>(ids->GetId(k + 1)));
      faceSource.push_back(cell);
    }
  }
  if (faces.empty()) throw InputError(what, path, "holds no triangles");
  mesh.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) mesh.F.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  ReadArrays(data->GetPointData(), mesh.pointData, data->GetNumberOfPoints());
  // Cell arrays are only meaningful when there are only polygons (VTK orders verts/lines first).
  if (data->GetNumberOfCells() == data->GetNumberOfPolys()) {
    std::map<std::string, DataArray> cells;
    ReadArrays(data->GetCellData(), cells, data->GetNumberOfCells());
    for (auto& [name, d] : cells) {
      DataArray expanded;
      expanded.integer = d.integer;
      expanded.values.resize(static_cast<Eigen::Index>(faceSource.size()), d.values.cols());
      for (std::size_t f = 0; f < faceSource.size(); ++f)
        expanded.values.row(static_cast<Eigen::Index>(f)) = d.values.row(faceSource[f]);
      mesh.cellData[name] = std::move(expanded);
    }
  }
  CheckMesh(mesh, path, what);
  if (fieldData) {
    fieldData->clear();
    ReadFieldArrays(data->GetFieldData(), *fieldData);
  }
  return mesh;
}

void WriteMesh(const TriangleMesh& mesh, const std::string& path, const std::string& what) {
  WriteMesh(mesh, path, what, FieldArrays{});
}

void WriteMesh(const TriangleMesh& mesh, const std::string& path, const std::string& what, const FieldArrays& fieldData) {
  vtkNew<vtkPolyData> data;
  data->SetPoints(ToPoints(mesh.V));
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(mesh.F.rows(), 3 * mesh.F.rows());
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const vtkIdType ids[3] = {static_cast<vtkIdType>(mesh.F(f, 0)), static_cast<vtkIdType>(mesh.F(f, 1)),
                             static_cast<vtkIdType>(mesh.F(f, 2))};
    polys->InsertNextCell(3, ids);
  }
  data->SetPolys(polys);
  WriteArrays(mesh.pointData, data->GetPointData());
  WriteArrays(mesh.cellData, data->GetCellData());
  WriteArrays(fieldData, data->GetFieldData());
  WritePolyData(data, path, what);
}

PolylineSet ReadPolylines(const std::string& path, const std::string& what) {
  vtkSmartPointer<vtkPolyData> data = ReadPolyData(path, what);
  PolylineSet set;
  auto* names = vtkStringArray::SafeDownCast(data->GetCellData()->GetAbstractArray("Name"));
  vtkCellArray* lines = data->GetLines();
  CheckCells(lines, data->GetNumberOfPoints(), "line", path, what);
  vtkNew<vtkIdList> ids;
  lines->InitTraversal();
  for (vtkIdType cell = 0; lines->GetNextCell(ids); ++cell) {
    Polyline line;
    const vtkIdType n = ids->GetNumberOfIds();
    line.closed = n > 2 && ids->GetId(0) == ids->GetId(n - 1);
    const vtkIdType count = line.closed ? n - 1 : n;
    line.points.resize(count, 3);
    for (vtkIdType k = 0; k < count; ++k) {
      if (ids->GetId(k) < 0 || ids->GetId(k) >= data->GetNumberOfPoints())
        throw InputError(what, path, "line " + std::to_string(cell) + " names point " + std::to_string(ids->GetId(k)) +
                                         ", but there are " + std::to_string(data->GetNumberOfPoints()) + " points");
      double p[3];
      data->GetPoint(ids->GetId(k), p);
      line.points.row(k) << p[0], p[1], p[2];
    }
    CheckFinitePoints(line.points, path, what);
    if (names && cell < names->GetNumberOfValues()) line.name = names->GetValue(cell);
    set.lines.push_back(std::move(line));
  }
  if (set.lines.empty()) throw InputError(what, path, "holds no polylines");
  ReadArrays(data->GetPointData(), set.pointData, data->GetNumberOfPoints());
  // Per-line arrays (SegmentId, IsCut, ...): the cells are the lines.
  if (data->GetNumberOfCells() == data->GetNumberOfLines())
    ReadArrays(data->GetCellData(), set.cellData, data->GetNumberOfCells());
  return set;
}

void WritePolylines(const PolylineSet& set, const std::string& path, const std::string& what) {
  Eigen::Index total = 0;
  for (const auto& l : set.lines) total += l.points.rows();
  Eigen::MatrixXd V(total, 3);
  vtkNew<vtkCellArray> cells;
  vtkNew<vtkStringArray> names;
  names->SetName("Name");
  Eigen::Index offset = 0;
  for (const auto& l : set.lines) {
    V.middleRows(offset, l.points.rows()) = l.points;
    std::vector<vtkIdType> ids;
    for (Eigen::Index k = 0; k < l.points.rows(); ++k) ids.push_back(offset + k);
    if (l.closed && !ids.empty()) ids.push_back(offset);
    cells->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    names->InsertNextValue(l.name);
    offset += l.points.rows();
  }
  vtkNew<vtkPolyData> data;
  data->SetPoints(ToPoints(V));
  data->SetLines(cells);
  data->GetCellData()->AddArray(names);
  WriteArrays(set.pointData, data->GetPointData());
  WriteArrays(set.cellData, data->GetCellData());
  WritePolyData(data, path, what);
}

}  // namespace colonmap::io
