// The stage reports (landmarks.json, flattening.json, registration.json): what the modules write is
// read back right, absent files and fields give the defaults, and every bad report is refused in
// one line naming the file and the field.
#include "Core/Testing/FreshTempDir.h"
#include "Core/Error.h"
#include "IO/StageReports.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <functional>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace colonmap;
using nlohmann::json;

namespace {

fs::path TempDir(const std::string& name) { return colonmap::FreshTempDir("reports", name); }

std::string Write(const fs::path& dir, const std::string& name, const std::string& text) {
  const fs::path p = dir / name;
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

using Reader = std::function<void(const std::string&)>;
const Reader kLandmarks = [](const std::string& p) { io::ReadLandmarksReport(p, "landmarks report"); };
const Reader kFlattening = [](const std::string& p) { io::ReadFlatteningReport(p, "supine flattening report"); };
const Reader kRegistration = [](const std::string& p) { io::ReadRegistrationReport(p, "registration report"); };

// The message of the refusal, or "" when the reader accepted the file.
std::string ErrorOf(const Reader& read, const std::string& path) {
  try {
    read(path);
  } catch (const Error& e) {
    return e.what();
  }
  return std::string();
}

// One line that names the user's file and says `problem`.
void ExpectRefused(const Reader& read, const std::string& path, const std::string& problem) {
  const std::string e = ErrorOf(read, path);
  SCOPED_TRACE(path + ": " + e);
  EXPECT_NE(e.find("'" + path + "': "), std::string::npos) << "names the file";
  EXPECT_NE(e.find(problem), std::string::npos) << "says: " << problem;
  EXPECT_EQ(e.find('\n'), std::string::npos) << "one line";
  EXPECT_EQ(e.find("json.exception"), std::string::npos) << "our words, not the parser's";
}

// A jointChoice as ColonLandmarks writes it, with the fields the next stages do not use.
json Joint(const std::string& pairedWith, bool consistent, bool fallback) {
  return {{"pairedWith", pairedWith}, {"consistent", consistent}, {"fallback", fallback}, {"alignmentCost", 0.06},
          {"flexures", {{"HF", {{"choice", "agreed"}, {"ownRulesArcLengthMm", 1076.9}}}}}};
}

json Match(const std::string& label, double su, double sv, double pu, double pv) {
  return {{"label", label}, {"supineUV", {su, sv}}, {"proneUV", {pu, pv}}, {"score", 0.9}};
}

}  // namespace

TEST(StageReports, WhatTheModulesWriteIsReadRight) {
  const fs::path dir = TempDir("valid");
  const json joint = Joint("prone", false, true);
  json landmarks = {{"segments", {{"A", {{"lengthMm", 210.0}}}}}, {"jointChoice", joint}, {"times", json::object()}};
  const io::LandmarksReport l = io::ReadLandmarksReport(Write(dir, "landmarks.json", landmarks.dump(2)), "landmarks report");
  ASSERT_TRUE(l.jointChoice);
  EXPECT_EQ(l.jointChoice->pairedWith, joint["pairedWith"].get<std::string>());
  EXPECT_EQ(l.jointChoice->consistent, joint["consistent"].get<bool>());
  EXPECT_EQ(l.jointChoice->fallback, joint["fallback"].get<bool>());

  // Widths as both width modes write them: 1 (unit) and a circumference in mm.
  const double widthA = 1.0, widthT = 157.25;
  json flattening = {{"segments",
                      {{"A", {{"flatWidth", widthA}, {"cut", "TO"}, {"flatLength", 1.5}, {"beltramiAbs", {{"mean", 0.01}}}}},
                       {"T", {{"flatWidth", widthT}, {"cut", "TL"}}},
                       {"D", {{"faces", 100}}}}},
                     {"missingSegments", json::array()},
                     {"widthMode", "unit"},
                     {"jointChoice", {{"pairedWith", ""}, {"consistent", true}, {"fallback", false}}}};
  const io::FlatteningReport f = io::ReadFlatteningReport(Write(dir, "flattening.json", flattening.dump(2)), "flattening report");
  ASSERT_EQ(f.segments.size(), 3u);
  EXPECT_EQ(*f.segments.at("A").flatWidth, widthA);
  EXPECT_EQ(*f.segments.at("A").cut, "TO");
  EXPECT_EQ(*f.segments.at("T").flatWidth, widthT);
  EXPECT_EQ(*f.segments.at("T").cut, "TL");
  EXPECT_FALSE(f.segments.at("D").flatWidth);
  EXPECT_FALSE(f.segments.at("D").cut);
  ASSERT_TRUE(f.jointChoice);
  EXPECT_TRUE(f.jointChoice->pairedWith.empty());

  const json matchesA = {Match("FA1", 0.25, 0.5, 0.3, 0.55), Match("FA2", 0.75, 1.25, 0.7, 1.2)};
  json registration = {{"method", "harmonic"},
                       {"segments",
                        {{"A", {{"features", {{"supine", 9}, {"matched", 2}, {"matches", matchesA}}}, {"trusted", true}}},
                         {"T", {{"features", {{"matches", json::array()}}}}},
                         {"D", {{"trusted", false}}}}},
                       {"flexuresJoint", true}};
  const io::RegistrationReport r =
      io::ReadRegistrationReport(Write(dir, "registration.json", registration.dump(2)), "registration report");
  EXPECT_EQ(r.method, "harmonic");
  ASSERT_EQ(r.matches.size(), 2u);  // A and T list matches, D lists no features
  ASSERT_EQ(r.matches.at("A").size(), matchesA.size());
  for (std::size_t k = 0; k < matchesA.size(); ++k) {
    EXPECT_EQ(r.matches.at("A")[k].label, matchesA[k]["label"].get<std::string>());
    for (int c = 0; c < 2; ++c) {
      EXPECT_EQ(r.matches.at("A")[k].supineUV(c), matchesA[k]["supineUV"][c].get<double>());
      EXPECT_EQ(r.matches.at("A")[k].proneUV(c), matchesA[k]["proneUV"][c].get<double>());
    }
  }
  EXPECT_TRUE(r.matches.at("T").empty());
  fs::remove_all(dir);
}

TEST(StageReports, AbsentFilesAndFieldsGiveTheDefaults) {
  const fs::path dir = TempDir("absent");
  const std::string missing = (dir / "missing.json").string();
  EXPECT_FALSE(io::ReadLandmarksReport(missing, "landmarks report").jointChoice);
  const io::FlatteningReport f = io::ReadFlatteningReport(missing, "flattening report");
  EXPECT_TRUE(f.segments.empty());
  EXPECT_FALSE(f.jointChoice);
  const io::RegistrationReport r = io::ReadRegistrationReport(missing, "registration report");
  EXPECT_EQ(r.method, io::RegistrationReport().method);
  EXPECT_TRUE(r.matches.empty());

  // An empty jointChoice: the defaults of each field. Unused fields and segments are not looked at.
  const std::string sparse = Write(dir, "sparse.json", R"({"jointChoice": {}, "segments": {"Q": 5, "A": {"lengthMm": "?"}},
    "method": "centerline"})");
  const io::JointChoice defaults;
  const io::LandmarksReport l = io::ReadLandmarksReport(sparse, "landmarks report");
  ASSERT_TRUE(l.jointChoice);
  EXPECT_EQ(l.jointChoice->pairedWith, defaults.pairedWith);
  EXPECT_EQ(l.jointChoice->consistent, defaults.consistent);
  EXPECT_EQ(l.jointChoice->fallback, defaults.fallback);
  const io::FlatteningReport fs2 = io::ReadFlatteningReport(sparse, "flattening report");
  ASSERT_EQ(fs2.segments.size(), 1u);
  EXPECT_FALSE(fs2.segments.at("A").flatWidth);
  const io::RegistrationReport r2 = io::ReadRegistrationReport(sparse, "registration report");
  EXPECT_EQ(r2.method, "centerline");
  EXPECT_TRUE(r2.matches.empty());
  fs::remove_all(dir);
}

TEST(StageReports, BadReportsAreRefusedInOneLineNamingTheFileAndTheField) {
  const fs::path dir = TempDir("bad");
  struct Case {
    const char* name;
    const char* text;
    std::vector<const Reader*> readers;
    std::string problem;
  };
  const std::vector<const Reader*> all = {&kLandmarks, &kFlattening, &kRegistration};
  const std::vector<const Reader*> joint = {&kLandmarks, &kFlattening};
  const std::vector<Case> cases = {
      {"broken", "{ \"jointChoice\": ", all, "is not valid JSON"},
      {"empty", "", all, "is not valid JSON"},
      {"trailing", "{} x", all, "is not valid JSON"},
      {"overflow", R"({"segments": {"A": {"flatWidth": 1e999}}})", all, "a number beyond the range of a double"},
      {"array", R"([{"jointChoice": {}}])", all, "is a JSON array, not an object"},
      {"number", "42", all, "is a JSON number, not an object"},
      {"paired-number", R"({"jointChoice": {"pairedWith": 7}})", joint, "'jointChoice.pairedWith' is a number, not a string"},
      {"consistent-string", R"({"jointChoice": {"consistent": "yes"}})", joint,
       "'jointChoice.consistent' is a string, not true or false"},
      {"fallback-number", R"({"jointChoice": {"fallback": 0}})", joint, "'jointChoice.fallback' is a number, not true or false"},
      {"joint-null", R"({"jointChoice": null})", joint, "'jointChoice' is a null, not an object"},
      {"segments-array", R"({"segments": [1]})", {&kFlattening, &kRegistration}, "'segments' is an array, not an object"},
      {"segment-number", R"({"segments": {"S": 3}})", {&kFlattening, &kRegistration}, "'segments.S' is a number, not an object"},
      {"width-string", R"({"segments": {"A": {"flatWidth": "1.0"}}})", {&kFlattening}, "'segments.A.flatWidth' is a string, not a number"},
      {"width-zero", R"({"segments": {"T": {"flatWidth": 0}}})", {&kFlattening}, "'segments.T.flatWidth' is 0, not in (0, "},
      {"width-negative", R"({"segments": {"D": {"flatWidth": -1.5}}})", {&kFlattening}, "'segments.D.flatWidth' is -1.5, not in (0, "},
      {"width-huge", R"({"segments": {"R": {"flatWidth": 1e300}}})", {&kFlattening}, "'segments.R.flatWidth' is 1e+300, not in (0, "},
      {"cut-number", R"({"segments": {"A": {"cut": 2}}})", {&kFlattening}, "'segments.A.cut' is a number, not a string"},
      {"method-number", R"({"method": 1})", {&kRegistration}, "'method' is a number, not a string"},
      {"features-array", R"({"segments": {"A": {"features": []}}})", {&kRegistration}, "'segments.A.features' is an array, not an object"},
      {"matches-object", R"({"segments": {"A": {"features": {"matches": {}}}}})", {&kRegistration},
       "'segments.A.features.matches' is an object, not an array"},
      {"match-number", R"({"segments": {"T": {"features": {"matches": [5]}}}})", {&kRegistration},
       "'segments.T.features.matches[0]' is a number, not an object"},
      {"match-no-prone", R"({"segments": {"A": {"features": {"matches": [{"supineUV": [0.1, 0.2]}]}}}})", {&kRegistration},
       "'segments.A.features.matches[0].proneUV' is missing"},
      {"uv-one", R"({"segments": {"A": {"features": {"matches": [{"supineUV": [0.1], "proneUV": [0.1, 0.2]}]}}}})",
       {&kRegistration}, "'segments.A.features.matches[0].supineUV' holds 1 values, not 2"},
      {"uv-string", R"({"segments": {"A": {"features": {"matches": [{"supineUV": [0.1, "0.2"], "proneUV": [0.1, 0.2]}]}}}})",
       {&kRegistration}, "'segments.A.features.matches[0].supineUV[1]' is a string, not a number"},
      {"uv-huge", R"({"segments": {"A": {"features": {"matches": [{"supineUV": [0.1, 0.2], "proneUV": [-1e300, 0.2]}]}}}})",
       {&kRegistration}, "'segments.A.features.matches[0].proneUV[0]' is -1e+300, not in ["},
      {"label-number", R"({"segments": {"A": {"features": {"matches": [{"label": 3, "supineUV": [0, 0], "proneUV": [0, 0]}]}}}})",
       {&kRegistration}, "'segments.A.features.matches[0].label' is a number, not a string"},
  };
  for (const Case& c : cases) {
    const std::string path = Write(dir, std::string(c.name) + ".json", c.text);
    for (const Reader* read : c.readers) ExpectRefused(*read, path, c.problem);
  }
  // A folder where the report should be is not taken for a missing report.
  fs::create_directories(dir / "folder.json");
  for (const Reader* read : all) ExpectRefused(*read, (dir / "folder.json").string(), "is a folder, not a JSON file");
  fs::remove_all(dir);
}

TEST(StageReports, LimitsAreInclusiveWhereTheyShouldBe) {
  // The largest width and the extreme flat coordinates are accepted; just beyond is refused.
  const fs::path dir = TempDir("limits");
  const json atLimit = {{"segments",
                         {{"A",
                           {{"flatWidth", io::kMaxFlatExtent},
                            {"features", {{"matches", {Match("F", -io::kMaxFlatExtent, io::kMaxFlatExtent, 0.0, 0.0)}}}}}}}}};
  const std::string ok = Write(dir, "ok.json", atLimit.dump());
  EXPECT_EQ(*io::ReadFlatteningReport(ok, "flattening report").segments.at("A").flatWidth, io::kMaxFlatExtent);
  EXPECT_EQ(io::ReadRegistrationReport(ok, "registration report").matches.at("A")[0].supineUV.x(), -io::kMaxFlatExtent);
  json beyond = atLimit;
  beyond["segments"]["A"]["flatWidth"] = io::kMaxFlatExtent * 1.001;
  ExpectRefused(kFlattening, Write(dir, "beyond.json", beyond.dump()), "'segments.A.flatWidth' is ");
  fs::remove_all(dir);
}
