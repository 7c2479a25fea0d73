// Surfaces and polylines: round trips with named arrays, the real GCA surface, bad inputs.
#include "Core/Error.h"
#include "IO/MeshIO.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace colonmap;

namespace {

fs::path TempDir(const std::string& name) {
  fs::path p = fs::temp_directory_path() / ("colonmap-meshio-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

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
