// Surfaces and polylines: round trips with named arrays, the real GCA surface, bad inputs.
#include "Core/Testing/FreshTempDir.h"
#include "Core/Error.h"
#include "IO/MeshIO.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace colonmap;

namespace {

fs::path TempDir(const std::string& name) { return colonmap::FreshTempDir("meshio", name); }

TriangleMesh Tetrahedron() {
  TriangleMesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1.5;
  m.F.resize(4, 3);
  m.F << 0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2;
  DataArray uv;
  uv.values.resize(4, 2);
  uv.values << 0, 0, 1, 0, 0, 1, 0.5, 0.25;
  m.pointData["FlatUV"] = uv;
  DataArray id;
  id.integer = true;
  id.values.resize(4, 1);
  id.values << 0, 1, 2, 4;
  m.pointData["SegmentId"] = id;
  DataArray k;
  k.values.resize(4, 1);
  k.values << 1.0, 1.5, 2.0, 6.0;
  m.cellData["Dilatation"] = k;
  return m;
}

}  // namespace

TEST(MeshIO, RoundTripKeepsGeometryTopologyAndArrays) {
  const fs::path dir = TempDir("roundtrip");
  const TriangleMesh m = Tetrahedron();
  for (const std::string ext : {".vtp", ".vtk"}) {
    const std::string path = (dir / ("m" + ext)).string();
    io::WriteMesh(m, path, "surface");
    const TriangleMesh r = io::ReadMesh(path, "surface");
    EXPECT_EQ(r.V, m.V) << ext;
    EXPECT_EQ(r.F, m.F) << ext;
    ASSERT_EQ(r.pointData.count("FlatUV"), 1u) << ext;
    EXPECT_EQ(r.pointData.at("FlatUV").values, m.pointData.at("FlatUV").values);
    EXPECT_TRUE(r.pointData.at("SegmentId").integer);
    EXPECT_FALSE(r.pointData.at("FlatUV").integer);
    EXPECT_EQ(r.cellData.at("Dilatation").values, m.cellData.at("Dilatation").values);
  }
  fs::remove_all(dir);
}

TEST(MeshIO, PolylinesKeepNamesAndClosure) {
  const fs::path dir = TempDir("lines");
  PolylineSet set;
  Polyline a{"TO", Eigen::MatrixXd::Random(5, 3), false};
  Polyline b{"loop", Eigen::MatrixXd::Random(4, 3), true};
  set.lines = {a, b};
  io::WritePolylines(set, (dir / "t.vtp").string(), "taeniae");
  const PolylineSet r = io::ReadPolylines((dir / "t.vtp").string(), "taeniae");
  ASSERT_EQ(r.lines.size(), 2u);
  EXPECT_EQ(r.lines[0].name, "TO");
  EXPECT_FALSE(r.lines[0].closed);
  EXPECT_TRUE(r.lines[1].closed);
  EXPECT_EQ(r.lines[1].points, b.points);
  fs::remove_all(dir);
}

TEST(MeshIO, ReadsRealLegacyVtkSurface) {
  const TriangleMesh m = io::ReadMesh(COLONMAP_SHARED_DIR "/data/gca-00020/SegmentedSurfaces/large-intestine-SF-SF+.vtk", "GCA surface");
  EXPECT_GT(m.V.rows(), 100);
  EXPECT_GT(m.F.rows(), 100);
  EXPECT_LE(m.F.maxCoeff(), m.V.rows() - 1);
  EXPECT_GE(m.F.minCoeff(), 0);
}

TEST(MeshIO, BadInputsGiveClearErrors) {
  const fs::path dir = TempDir("bad");
  std::ofstream(dir / "garbage.vtp") << "<VTKFile this is not";
  std::ofstream(dir / "x.obj") << "v 0 0 0";
  const auto errorOf = [](const std::string& p) {
    try { io::ReadMesh(p, "surface"); } catch (const Error& e) { return std::string(e.what()); }
    return std::string();
  };
  EXPECT_NE(errorOf((dir / "missing.vtp").string()).find("file does not exist"), std::string::npos);
  EXPECT_NE(errorOf((dir / "garbage.vtp").string()).find("surface '"), std::string::npos);
  EXPECT_NE(errorOf((dir / "x.obj").string()).find("unknown surface format"), std::string::npos);
  EXPECT_NE(errorOf(dir.string()).find("is a folder"), std::string::npos);
  fs::remove_all(dir);
}

namespace {

std::string ReadError(const std::string& path) {
  try {
    io::ReadMesh(path, "surface");
  } catch (const Error& e) {
    return e.what();
  }
  return "read without error";
}

void Spit(const fs::path& p, const std::string& bytes) { std::ofstream(p, std::ios::binary) << bytes; }

// A small XML PolyData triangle in ascii, with `fieldData` elements and the Points array's
// attributes as given.
std::string AsciiTriangle(const std::string& fieldData = "", const std::string& points = "NumberOfComponents=\"3\"",
                          const std::string& connectivity = "0 1 2") {
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <PolyData>\n" + fieldData +
         "    <Piece NumberOfPoints=\"3\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
         "NumberOfPolys=\"1\">\n"
         "      <Points><DataArray type=\"Float32\" Name=\"Points\" " + points +
         " format=\"ascii\">0 0 0 1 0 0 0 1 0</DataArray></Points>\n"
         "      <Polys>\n"
         "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">" + connectivity + "</DataArray>\n"
         "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">3</DataArray>\n"
         "      </Polys>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
}

// A triangle whose points are appended raw, "compressed" with zlib, behind the compression header
// given (UInt64 words: block count, block size, last block size, first block's compressed size).
// The checks refuse the header before anything is decompressed, so the block is filler.
std::string CompressedTriangle(std::uint64_t blocks, std::uint64_t blockSize, std::uint64_t lastSize,
                               std::uint64_t compressedSize, const std::string& compressor = "vtkZLibDataCompressor") {
  std::string bytes =
      "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\" compressor=\"" +
      compressor + "\">\n  <PolyData>\n"
      "    <Piece NumberOfPoints=\"3\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
      "NumberOfPolys=\"1\">\n"
      "      <Points><DataArray type=\"Float32\" Name=\"Points\" NumberOfComponents=\"3\" format=\"appended\" "
      "offset=\"0\"/></Points>\n"
      "      <Polys>\n"
      "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 2</DataArray>\n"
      "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">3</DataArray>\n"
      "      </Polys>\n    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n   _";
  for (const std::uint64_t word : {blocks, blockSize, lastSize, compressedSize})
    for (int b = 0; b < 8; ++b) bytes += static_cast<char>((word >> (8 * b)) & 0xff);
  return bytes + std::string(36, 'x') + "\n  </AppendedData>\n</VTKFile>\n";
}

}  // namespace

// Inputs the mesh fuzz target (Testing/Fuzz/FuzzMesh.cxx) found, each refused in one line before VTK
// crashes, allocates by a number from the file, or a wrong mesh gets through.
TEST(MeshIO, FuzzFoundInputsGiveClearErrors) {
  const fs::path dir = TempDir("fuzz");
  const auto expect = [&](const std::string& name, const std::string& bytes, const std::string& problem) {
    const std::string p = (dir / name).string();
    Spit(p, bytes);
    EXPECT_EQ(ReadError(p), "surface '" + p + "': " + problem) << name;
  };
  // Our bugs: a point id of 2^32 became point 0 (int cast); decreasing legacy offsets made VTK's
  // traversal read before the connectivity (now our own legacy reader refuses them).
  expect("id.vtp", AsciiTriangle("", "NumberOfComponents=\"3\"", "0 1 4294967296"),
         "polygon 0 names point 4294967296, but there are 3 points");
  expect("offsets.vtk",
         "# vtk DataFile Version 5.1\nvtk output\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\n"
         "POLYGONS 3 3\nOFFSETS vtktypeint64\n0 3 1\nCONNECTIVITY vtktypeint64\n0 1 2\n",
         "has POLYGONS offsets that do not start at 0 and end at the connectivity's size");
  // VTK's: crashes (null array, out-of-range string, std::length_error) and a leak.
  expect("fieldtype.vtp",
         AsciiTriangle("    <FieldData><DataArray type=\"Ltring\" Name=\"SPACE\" NumberOfTuples=\"1\" "
                       "format=\"ascii\">0</DataArray></FieldData>\n"),
         "field data array 'SPACE' has no type VTK knows ('Ltring')");
  expect("points2.vtp", AsciiTriangle("", "NumberOfComponents=\"2\""),
         "points array 'Points' does not have 3 components");
  expect("components.vtp",
         AsciiTriangle("    <FieldData><DataArray type=\"Int32\" Name=\"T\" NumberOfComponents=\"-13\" "
                       "NumberOfTuples=\"1\" format=\"ascii\">0</DataArray></FieldData>\n"),
         "array 'T' declares -13 components");
  expect("manycomponents.vtp",
         AsciiTriangle("    <FieldData><DataArray type=\"Int32\" Name=\"T\" NumberOfComponents=\"99999999999\" "
                       "NumberOfTuples=\"1\" format=\"ascii\">0</DataArray></FieldData>\n"),
         "array 'T' declares 99999999999 components");
  expect("strings.vtp",
         AsciiTriangle("    <FieldData><Array type=\"String\" Name=\"SPACE\" NumberOfTuples=\"1\" format=\"ascii\">"
                       "76 80 83 0 0</Array></FieldData>\n"),
         "string array 'SPACE' holds 2 strings, not 1");
  std::string shortCells = AsciiTriangle();
  shortCells.insert(shortCells.find("      <Points>"),
                    "      <CellData><DataArray type=\"Float32\" Name=\"K\" format=\"ascii\"></DataArray>"
                    "</CellData>\n");
  expect("shortcells.vtp", shortCells, "cell data array 'K' does not hold the 1 values its cells need");
  std::string twoNames = AsciiTriangle();
  twoNames.insert(twoNames.find("      <Points>"),
                  "      <CellData><DataArray type=\"Int8\" Name=\"A\" format=\"ascii\">1</DataArray>"
                  "<DataArray type=\"Int8\" Name=\"A\" format=\"ascii\">2</DataArray></CellData>\n");
  expect("twonames.vtp", twoNames, "CellData has two arrays named 'A'");
  std::string shortStrings = AsciiTriangle();
  shortStrings.insert(shortStrings.find("      <Points>"),
                      "      <PointData><Array type=\"String\" Name=\"S\" format=\"ascii\">65 0</Array>"
                      "</PointData>\n");
  expect("shortstrings.vtp", shortStrings, "string array 'S' holds 1 strings, not 3");
  std::string noCells = AsciiTriangle();
  noCells.erase(noCells.find("      <Polys>"), noCells.find("    </Piece>") - noCells.find("      <Polys>"));
  expect("nocells.vtp", noCells, "declares 1 Polys but has no Polys offsets and connectivity");
  std::string bigger = AsciiTriangle();
  bigger.replace(bigger.find("NumberOfPoints=\"3\""), 18, "NumberOfPoints=\"1000000000\"");
  const std::string big = (dir / "count.vtp").string();
  Spit(big, bigger);
  EXPECT_EQ(ReadError(big), "surface '" + big + "': declares arrays that need at least 3000000001 bytes of the file, "
                            "which has " + std::to_string(fs::file_size(big)));
  // VTK's: allocations by a compression header (up to 2^62 bytes).
  expect("compressor.vtp", CompressedTriangle(1, 32768, 36, 36, "vtkFooDataCompressor"),
         "names a compressor VTK does not know ('vtkFooDataCompressor')");
  expect("blocks.vtp", CompressedTriangle(std::uint64_t{1} << 30, 32768, 36, 36),
         "compressed array 'Points' has a header declaring 1073741824 blocks, more than the file can hold");
  expect("last.vtp", CompressedTriangle(1, 32768, std::uint64_t{1} << 30, 36),
         "compressed array 'Points' has a header declaring 1 blocks of 32768 bytes and a last block of "
         "1073741824 bytes");
  expect("size.vtp", CompressedTriangle(1, 32768, 36, std::uint64_t{1} << 30),
         "compressed array 'Points' has a block of 1073741824 bytes, larger than the file");
  expect("ratio.vtp", CompressedTriangle(1, 65536, 36000, 20),
         "compressed array 'Points' has a block of 20 bytes said to decompress to 36000 bytes");
  fs::remove_all(dir);
}

// The checks before VTK reads must let real files through: several compression blocks, string
// arrays (polyline names), field data.
TEST(MeshIO, LargeCompressedFilesPassTheChecks) {
  const fs::path dir = TempDir("large");
  TriangleMesh m;
  const int n = 20000;
  m.V = Eigen::MatrixXd::Random(n, 3);
  m.F.resize(n - 2, 3);
  for (int f = 0; f < n - 2; ++f) m.F.row(f) << f, f + 1, f + 2;
  DataArray zeros;
  zeros.values = Eigen::MatrixXd::Zero(n, 4);
  m.pointData["Zeros"] = zeros;
  io::FieldArrays field;
  field["Carried"] = DataArray{Eigen::MatrixXd::Ones(5000, 3), false};
  const std::string path = (dir / "big.vtp").string();
  io::WriteMesh(m, path, "surface", field);
  io::FieldArrays back;
  const TriangleMesh r = io::ReadMesh(path, "surface", &back);
  EXPECT_EQ(r.V, m.V);
  EXPECT_EQ(r.F, m.F);
  EXPECT_EQ(back.at("Carried").values, field.at("Carried").values);
  fs::remove_all(dir);
}
