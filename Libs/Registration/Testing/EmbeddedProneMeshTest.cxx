// The prone mesh carried inside registration.vtp (issue 23): written and read back bit for bit,
// found by ReadRegistration with no file beside it, and refused with a clear message when the
// copy is damaged.
#include "Core/Error.h"
#include "IO/MeshIO.h"
#include "Registration/EmbeddedProneMesh.h"
#include "Registration/PointTransfer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

using namespace colonmap;
using namespace colonmap::registration;
namespace fs = std::filesystem;

namespace {

// Two triangles with values that do not survive a float round trip (1/3, 0.1).
TriangleMesh Square(double z) {
  TriangleMesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, z, 1.0 / 3.0, 0, z, 1.0 / 3.0, 0.1, z, 0, 0.1, z;
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 0, 2, 3;
  m.pointData["SupineTriangleId"] = DataArray{Eigen::MatrixXd(Eigen::Vector4d(0, 1, 1, 0)), true};
  Eigen::MatrixXd bary(4, 3);
  bary << 1, 0, 0, 0, 1, 0, 0, 0.3, 0.7, 0, 0, 1;
  m.pointData["SupineBarycentric"] = DataArray{bary, false};
  m.cellData["Dilatation"] = DataArray{Eigen::MatrixXd(Eigen::Vector2d(1.0 / 7.0, 2.0)), false};
  return m;
}

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("colonmap-embedded-" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

}  // namespace

TEST(EmbeddedProneMesh, SurvivesTheFileBitForBit) {
  TempDir dir;
  const TriangleMesh supine = Square(0), prone = Square(5);
  io::FieldArrays field;
  EmbedProneMesh(prone, &field);
  const std::string path = (dir.path / "renamed.vtp").string();
  io::WriteMesh(supine, path, "registration", field);
  io::FieldArrays back;
  const TriangleMesh read = io::ReadMesh(path, "registration", &back);
  EXPECT_EQ(read.pointData.size(), supine.pointData.size());  // the supine arrays are unchanged
  const std::optional<TriangleMesh> p = EmbeddedProneMesh(back, path);
  ASSERT_TRUE(p.has_value());
  EXPECT_TRUE(p->V == prone.V);
  EXPECT_TRUE(p->F == prone.F);
  ASSERT_EQ(p->pointData.size(), 2u);
  EXPECT_TRUE(p->pointData.at("SupineBarycentric").values == prone.pointData.at("SupineBarycentric").values);
  EXPECT_TRUE(p->pointData.at("SupineTriangleId").integer);
  EXPECT_TRUE(p->cellData.at("Dilatation").values == prone.cellData.at("Dilatation").values);
  // ReadRegistration: nothing beside the file, the copy is used.
  const RegistrationMeshes r = ReadRegistration(path);
  EXPECT_TRUE(r.prone.V == prone.V);
}

TEST(EmbeddedProneMesh, AbsentIsNotAnError) {
  EXPECT_FALSE(EmbeddedProneMesh(io::FieldArrays{}, "r.vtp").has_value());
}

TEST(EmbeddedProneMesh, DamagedCopyIsRefused) {
  io::FieldArrays field;
  EmbedProneMesh(Square(5), &field);
  io::FieldArrays noTriangles = field;
  noTriangles.erase("ProneMeshTriangles");
  EXPECT_THROW(EmbeddedProneMesh(noTriangles, "r.vtp"), Error);
  io::FieldArrays outOfRange = field;
  outOfRange["ProneMeshTriangles"].values(1, 2) = 9;
  try {
    EmbeddedProneMesh(outOfRange, "r.vtp");
    FAIL() << "triangle id out of range accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("r.vtp"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("names point 9"), std::string::npos) << e.what();
  }
  io::FieldArrays shortArray = field;
  shortArray["ProneMeshPointData_SupineTriangleId"].values.conservativeResize(3, 1);
  EXPECT_THROW(EmbeddedProneMesh(shortArray, "r.vtp"), Error);
}
