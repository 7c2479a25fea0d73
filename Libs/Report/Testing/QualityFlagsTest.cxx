#include "Report/QualityFlags.h"

#include <gtest/gtest.h>

using namespace colonmap::report;
using nlohmann::json;

namespace {

json Landmarks(double hf = 1080.0) {
  json l;
  const char* segs[5] = {"A", "T", "D", "S", "R"};
  for (int i = 0; i < 5; ++i) l["segments"][segs[i]] = {{"lengthMm", 200.0 + 10 * i}, {"cutTaenia", "TO"}, {"taeniaConfidence", 0.3}};
  l["flexures"] = {{"RSJ", {{"arcLengthMm", 118.0}}}, {"DSJ", {{"arcLengthMm", 419.0}}},
                   {"SF", {{"arcLengthMm", 708.0}}}, {"HF", {{"arcLengthMm", hf}}}};
  return l;
}

json Flattening(int flips = 0, double mu = 0.01) {
  json f{{"flippedTriangles", flips}};
  for (const char* s : {"A", "T", "D", "S", "R"}) f["segments"][s]["beltramiAbs"]["mean"] = mu;
  return f;
}

json Registration(int flips = 0, int matched = 5) {
  json r{{"flippedTriangles", flips}, {"method", "harmonic"}};
  for (const char* s : {"A", "T", "D", "S", "R"}) r["segments"][s]["features"]["matched"] = matched;
  return r;
}

StageSummaries Good() {
  StageSummaries s;
  s.landmarks[0] = s.landmarks[1] = Landmarks();
  s.flattening[0] = s.flattening[1] = Flattening();
  s.registration = Registration();
  return s;
}

const QualityFlag& Find(const std::vector<QualityFlag>& flags, const std::string& prefix) {
  for (const auto& f : flags)
    if (f.name.rfind(prefix, 0) == 0) return f;
  throw std::runtime_error("no flag " + prefix);
}

}  // namespace

TEST(QualityFlags, AGoodRunHasOnlyOkFlags) {
  const auto flags = AssessQuality(Good());
  EXPECT_EQ(flags.size(), 9u);
  for (const auto& f : flags) EXPECT_TRUE(f.ok) << f.name << ": " << f.detail;
}

TEST(QualityFlags, EachProblemRaisesItsFlag) {
  StageSummaries s = Good();
  s.landmarks[1] = Landmarks(600.0);  // HF before SF: out of order
  s.landmarks[1]["segments"]["R"]["taeniaConfidence"] = 0.05;
  s.landmarks[0]["segments"]["T"]["cutTaenia"] = "TL";
  s.landmarks[0]["segments"]["S"]["lengthMm"] = 500.0;
  s.flattening[0] = Flattening(3);
  s.flattening[1] = Flattening(0, 0.2);
  s.registration = Registration(1, 2);
  const auto flags = AssessQuality(s);
  EXPECT_TRUE(Find(flags, "Four flexures found (supine)").ok);
  EXPECT_FALSE(Find(flags, "Four flexures found (prone)").ok);
  EXPECT_FALSE(Find(flags, "Taenia confidence").ok);
  EXPECT_NE(Find(flags, "Taenia confidence").detail.find("R prone 0.05"), std::string::npos);
  EXPECT_FALSE(Find(flags, "Same cut taenia").ok);
  EXPECT_FALSE(Find(flags, "Segment lengths").ok);
  EXPECT_FALSE(Find(flags, "Flattening conformal, no flips (supine)").ok);
  EXPECT_FALSE(Find(flags, "Flattening conformal, no flips (prone)").ok);
  EXPECT_FALSE(Find(flags, "Registration one-to-one").ok);
  EXPECT_FALSE(Find(flags, "Features matched").ok);
}

TEST(QualityFlags, MissingStagesGiveNoFlagsAndMissingFlexuresAreNamed) {
  StageSummaries s;
  EXPECT_TRUE(AssessQuality(s).empty());
  s.landmarks[0] = Landmarks();
  s.landmarks[0]["flexures"].erase("DSJ");
  const auto flags = AssessQuality(s);
  ASSERT_EQ(flags.size(), 1u);
  EXPECT_FALSE(flags[0].ok);
  EXPECT_NE(flags[0].detail.find("DSJ missing"), std::string::npos);
}

TEST(QualityFlags, JointFlexuresAreTrustedOnlyWithAnOrderedChoiceAndAGoodAlignment) {
  const auto joint = [](bool consistent, bool fallback, double cost) {
    json j{{"pairedWith", "prone"}, {"consistent", consistent}, {"fallback", fallback}, {"alignmentCost", cost}};
    for (const char* f : {"HF", "SF", "DSJ", "RSJ"}) j["flexures"][f] = {{"choice", "agreed"}};
    j["flexures"]["DSJ"]["choice"] = "carried from supine";
    return j;
  };
  StageSummaries s = Good();
  s.landmarks[0]["jointChoice"] = joint(true, false, 0.08);
  const auto flags = AssessQuality(s);  // Find returns a reference into it (found by ASan)
  const QualityFlag& ok = Find(flags, "Flexures chosen jointly");
  EXPECT_TRUE(ok.ok) << ok.detail;
  EXPECT_NE(ok.detail.find("DSJ carried from supine"), std::string::npos);
  s.landmarks[0]["jointChoice"] = joint(false, true, 0.08);
  const auto fallback = AssessQuality(s);
  EXPECT_FALSE(Find(fallback, "Flexures chosen jointly").ok);
  EXPECT_NE(Find(fallback, "Flexures chosen jointly").detail.find("not trusted"), std::string::npos);
  s.landmarks[0]["jointChoice"] = joint(true, false, 0.6);
  EXPECT_FALSE(Find(AssessQuality(s), "Flexures chosen jointly").ok);
  // A single-scan landmark run has no joint choice and no such flag.
  s.landmarks[0].erase("jointChoice");
  EXPECT_THROW(Find(AssessQuality(s), "Flexures chosen jointly"), std::runtime_error);
  s.landmarks[0]["jointChoice"] = json{{"pairedWith", ""}, {"consistent", true}, {"fallback", false}};
  EXPECT_THROW(Find(AssessQuality(s), "Flexures chosen jointly"), std::runtime_error);
}

TEST(QualityFlags, UntrustedSegmentsAreFlagged) {
  StageSummaries s = Good();
  EXPECT_THROW(Find(AssessQuality(s), "Segments trusted"), std::runtime_error);  // an older registration.json
  s.registration["untrustedSegments"] = "";
  for (const char* seg : {"A", "T", "D", "S", "R"})
    s.registration["segments"][seg]["trusted"] = true, s.registration["segments"][seg]["expectedErrorMm"] = 1.5;
  EXPECT_TRUE(Find(AssessQuality(s), "Segments trusted").ok);
  s.registration["untrustedSegments"] = "S";
  s.registration["segments"]["S"]["trusted"] = false;
  const QualityFlag f = Find(AssessQuality(s), "Segments trusted");
  EXPECT_FALSE(f.ok);
  EXPECT_NE(f.detail.find("S NO"), std::string::npos) << f.detail;
}
