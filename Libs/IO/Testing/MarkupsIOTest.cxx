// Point lists: schema-valid output, LPS and RAS reading, .fcsv, bad inputs.
#include "Core/Testing/FreshTempDir.h"
#include "Core/Error.h"
#include "IO/MarkupsIO.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace colonmap;

namespace {

fs::path TempDir(const std::string& name) { return colonmap::FreshTempDir("markups", name); }

MarkupList Sample() {
  MarkupList list;
  list.name = "findings";
  list.points.push_back({"P1", {10.5, -20.25, 30.0}, "sessile polyp"});
  list.points.push_back({"P2", {-1.0 / 3.0, 2.0, 1e-3}, ""});
  return list;
}

}  // namespace

TEST(MarkupsIO, WrittenFileValidatesAgainstSlicerSchema) {
  const fs::path dir = TempDir("schema");
  const std::string path = (dir / "f.mrk.json").string();
  io::WriteMarkups(Sample(), path, "findings");
  const std::string command = std::string(COLONMAP_PYTHON) +
      " -c \"import json,jsonschema,sys; jsonschema.validate(json.load(open(sys.argv[1])), json.load(open(sys.argv[2])))\" " +
      path + " " + COLONMAP_SHARED_DIR "/schemas/markups-schema-v1.0.3.json";
  EXPECT_EQ(std::system(command.c_str()), 0);
  // A file the schema must reject proves the check can fail.
  std::ofstream(dir / "bad.mrk.json") << R"({"@schema": "x", "markups": [{"type": "Banana"}]})";
  const std::string bad = std::string(COLONMAP_PYTHON) +
      " -c \"import json,jsonschema,sys; jsonschema.validate(json.load(open(sys.argv[1])), json.load(open(sys.argv[2])))\" " +
      (dir / "bad.mrk.json").string() + " " + COLONMAP_SHARED_DIR "/schemas/markups-schema-v1.0.3.json 2>/dev/null";
  EXPECT_NE(std::system(bad.c_str()), 0);
  fs::remove_all(dir);
}

TEST(MarkupsIO, LpsAndRasFilesReadBackIdentically) {
  const fs::path dir = TempDir("ras");
  const std::string lps = (dir / "lps.mrk.json").string();
  io::WriteMarkups(Sample(), lps, "findings");
  // The same points written by a host in RAS.
  std::ofstream(dir / "ras.mrk.json") << R"({"@schema": "x", "markups": [{"type": "Fiducial", "coordinateSystem": "RAS",
    "controlPoints": [{"label": "P1", "position": [-10.5, 20.25, 30.0]}, {"label": "P2", "position": [0.3333333333333333, -2.0, 0.001]}]}]})";
  const MarkupList a = io::ReadMarkups(lps, "lps"), b = io::ReadMarkups((dir / "ras.mrk.json").string(), "ras");
  ASSERT_EQ(a.points.size(), 2u);
  ASSERT_EQ(b.points.size(), 2u);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(a.points[i].label, Sample().points[i].label);
    EXPECT_EQ(a.points[i].position, Sample().points[i].position);  // exact round trip
    EXPECT_LT((a.points[i].position - b.points[i].position).norm(), 1e-12);
  }
  EXPECT_EQ(a.points[0].description, "sessile polyp");
  fs::remove_all(dir);
}

TEST(MarkupsIO, FcsvReadsInBothCoordinateSystems) {
  const fs::path dir = TempDir("fcsv");
  io::WriteMarkups(Sample(), (dir / "a.fcsv").string(), "findings");
  const MarkupList a = io::ReadMarkups((dir / "a.fcsv").string(), "findings");
  ASSERT_EQ(a.points.size(), 2u);
  EXPECT_LT((a.points[1].position - Sample().points[1].position).norm(), 1e-12);
  EXPECT_EQ(a.points[1].label, "P2");
  std::ofstream(dir / "ras.fcsv") << "# Markups fiducial file version = 4.10\n# CoordinateSystem = 0\n"
                                     "# columns = id,x,y,z,ow,ox,oy,oz,vis,sel,lock,label,desc,associatedNodeID\n"
                                     "vtkMRMLMarkupsFiducialNode_0,1,2,3,0,0,0,1,1,1,0,F-1,,\n";
  const MarkupList r = io::ReadMarkups((dir / "ras.fcsv").string(), "findings");
  ASSERT_EQ(r.points.size(), 1u);
  EXPECT_EQ(r.points[0].position, Eigen::Vector3d(-1, -2, 3));
  EXPECT_EQ(r.points[0].label, "F-1");
  fs::remove_all(dir);
}

TEST(MarkupsIO, BadInputsGiveClearErrors) {
  const fs::path dir = TempDir("bad");
  std::ofstream(dir / "broken.mrk.json") << "{ not json";
  std::ofstream(dir / "other.json") << R"({"a": 1})";
  const auto errorOf = [](const std::string& p) {
    try { io::ReadMarkups(p, "findings"); } catch (const Error& e) { return std::string(e.what()); }
    return std::string();
  };
  EXPECT_NE(errorOf((dir / "missing.mrk.json").string()).find("file does not exist"), std::string::npos);
  EXPECT_NE(errorOf((dir / "broken.mrk.json").string()).find("is not valid JSON"), std::string::npos);
  EXPECT_NE(errorOf((dir / "other.json").string()).find("not a Slicer markups file"), std::string::npos);
  EXPECT_NE(errorOf((dir / "x.csv").string()).find("unknown point list format"), std::string::npos);
  fs::remove_all(dir);
}
