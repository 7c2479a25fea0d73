// Argument parsing driven by the XML: defaults, every type, constraints, points, --help.
#include "AllTypesXml.h"
#include "CLI/Arguments.h"
#include "CLI/ModuleDescription.h"
#include "Core/Error.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

using namespace colonmap;
using namespace colonmap::cli;

namespace {

Arguments Parse(std::vector<std::string> args) {
  static const ModuleDescription module = ParseModuleDescription(AllTypesXml());
  args.insert(args.begin(), "slicer:0x1234");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  return ParseCommandLine(module, "AllTypes", static_cast<int>(argv.size()), argv.data());
}

std::string ErrorOf(std::vector<std::string> args) {
  try {
    Parse(std::move(args));
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ModuleDescription, ReadsEveryParameter) {
  const ModuleDescription m = ParseModuleDescription(AllTypesXml());
  EXPECT_EQ(m.title, "All Types");
  EXPECT_EQ(m.version, "1.2.3");
  EXPECT_EQ(m.Parameters().size(), 21u);
  const auto* count = m.Find("count");
  ASSERT_NE(count, nullptr);
  EXPECT_EQ(count->flag, "c");
  EXPECT_TRUE(count->hasMinimum && count->hasMaximum);
  EXPECT_DOUBLE_EQ(count->maximum, 10.0);
  EXPECT_EQ(m.Find("direction")->elements.size(), 2u);
  EXPECT_EQ(m.Find("outputVolume")->index, 1);
  EXPECT_TRUE(m.Find("total")->IsReturnParameter());
  EXPECT_FALSE(m.Find("stats")->IsReturnParameter());
  EXPECT_TRUE(m.HasReturnParameters());
  EXPECT_EQ(m.Find("findings")->fileExtensions, ".mrk.json");
  EXPECT_EQ(m.Find("rasSeeds")->coordinateSystem, "ras");
}

TEST(ModuleDescription, RejectsMalformedDescriptions) {
  EXPECT_THROW(ParseModuleDescription("<executable><parameters><integer><label>x</label></integer></parameters></executable>"), Error);
  EXPECT_THROW(ParseModuleDescription("<executable><parameters><widget><name>x</name></widget></parameters></executable>"), Error);
  EXPECT_THROW(ParseModuleDescription("<executable><parameters><image><name>a</name><index>0</index><longflag>a</longflag></image></parameters></executable>"), Error);
  EXPECT_THROW(ParseModuleDescription("<notamodule/>"), Error);
  EXPECT_THROW(ParseModuleDescription("<executable><parameters"), Error);
  // Found writing the fuzz contract (issue 24): a NaN or infinite bound switched the range check
  // off, and atoi read "-5" as "no index" and "x" as index 0.
  const auto errorOf = [](const std::string& parameter) {
    try {
      ParseModuleDescription("<executable><parameters>" + parameter + "</parameters></executable>");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(errorOf("<integer><name>n</name><constraints><minimum>nan</minimum></constraints></integer>"),
            "module description: a <integer> parameter has <minimum> 'nan', not a finite number");
  EXPECT_NE(errorOf("<double><name>d</name><constraints><maximum>1e999</maximum></constraints></double>"), "");
  EXPECT_NE(errorOf("<double><name>d</name><constraints><maximum>ten</maximum></constraints></double>"), "");
  EXPECT_EQ(errorOf("<image><name>a</name><index>-5</index></image>"),
            "module description: a <image> parameter has <index> '-5', not a non-negative integer");
  EXPECT_NE(errorOf("<image><name>a</name><index>x</index></image>"), "");
  EXPECT_EQ(errorOf("<image><name>a</name><index>2</index></image>"), "");
}

TEST(CommandLine, AbsentFlagsTakeXmlDefaults) {
  const Arguments a = Parse({"in.nrrd", "out.nrrd"});
  EXPECT_EQ(a.GetInt("count"), 3);
  EXPECT_FLOAT_EQ(static_cast<float>(a.GetDouble("ratio")), 0.25f);
  EXPECT_DOUBLE_EQ(a.GetDouble("sigma"), 1.5);
  EXPECT_FALSE(a.GetBool("verbose"));
  EXPECT_EQ(a.GetString("title"), "colon");
  EXPECT_EQ(a.GetString("direction"), "supineToProne");
  EXPECT_EQ(a.GetIntVector("sizes"), (std::vector<long>{1, 2, 3}));
  EXPECT_EQ(a.GetDoubleVector("spacing"), (std::vector<double>{0.7, 0.7, 1.0}));
  EXPECT_EQ(a.GetStringVector("names"), (std::vector<std::string>{"a", "b"}));
  EXPECT_TRUE(a.GetPoints("seeds").empty());
  EXPECT_FALSE(a.Has("notes"));
  EXPECT_FALSE(a.Given("count"));
  EXPECT_EQ(a.GetString("inputVolume"), "in.nrrd");
  EXPECT_EQ(a.GetString("outputVolume"), "out.nrrd");
}

TEST(CommandLine, ParsesEveryTypeInAnyFlagOrder) {
  const Arguments a = Parse({"--seeds", "1,2,3", "--direction", "proneToSupine", "-c", "7",
                             "--ratio", "0.5", "--sigma", "2", "--verbose", "--title", "a b",
                             "--sizes", "4,5", "--weights", "1.5,2.5", "--spacing", "1,1,2",
                             "--names", "x,y,z", "--seeds", "4,5,6", "--rasSeeds", "1,2,3",
                             "--box", "0,0,0,5,5,5", "--notes", "n.txt", "--workDir", "/tmp",
                             "--surface", "s.vtp", "--findings", "f.mrk.json", "--stats", "t.tsv",
                             "in.nrrd", "out.nrrd"});
  EXPECT_EQ(a.GetInt("count"), 7);
  EXPECT_TRUE(a.Given("count"));
  EXPECT_DOUBLE_EQ(a.GetDouble("ratio"), 0.5);
  EXPECT_TRUE(a.GetBool("verbose"));
  EXPECT_EQ(a.GetString("title"), "a b");
  EXPECT_EQ(a.GetString("direction"), "proneToSupine");
  EXPECT_EQ(a.GetIntVector("sizes"), (std::vector<long>{4, 5}));
  EXPECT_EQ(a.GetDoubleVector("weights"), (std::vector<double>{1.5, 2.5}));
  EXPECT_EQ(a.GetStringVector("names").size(), 3u);
  const auto seeds = a.GetPoints("seeds");
  ASSERT_EQ(seeds.size(), 2u);
  EXPECT_EQ(seeds[1], Eigen::Vector3d(4, 5, 6));
  // RAS points come back in LPS.
  ASSERT_EQ(a.GetPoints("rasSeeds").size(), 1u);
  EXPECT_EQ(a.GetPoints("rasSeeds")[0], Eigen::Vector3d(-1, -2, 3));
  EXPECT_EQ(a.GetDoubleVector("box").size(), 6u);
  EXPECT_EQ(a.GetString("findings"), "f.mrk.json");
  EXPECT_TRUE(a.Has("stats"));
}

TEST(CommandLine, RejectsOutOfRangeAndMalformedValuesClearly) {
  EXPECT_NE(ErrorOf({"--count", "11", "i", "o"}).find("--count (count): value 11 is above the maximum"), std::string::npos);
  EXPECT_NE(ErrorOf({"--count", "0", "i", "o"}).find("below the minimum"), std::string::npos);
  EXPECT_NE(ErrorOf({"--count", "2.5", "i", "o"}).find("not an integer"), std::string::npos);
  EXPECT_NE(ErrorOf({"--sigma", "nan", "i", "o"}).find("not a finite number"), std::string::npos);
  EXPECT_NE(ErrorOf({"--direction", "sideways", "i", "o"}).find("not one of: supineToProne, proneToSupine"), std::string::npos);
  EXPECT_NE(ErrorOf({"--seeds", "1,2", "i", "o"}).find("not 3 comma-separated numbers"), std::string::npos);
  EXPECT_NE(ErrorOf({"--spacing", "1,x,1", "i", "o"}).find("comma-separated list"), std::string::npos);
  EXPECT_NE(ErrorOf({"--box", "1,2,3", "i", "o"}).find("not 6"), std::string::npos);
  EXPECT_NE(ErrorOf({"--nosuchflag", "1", "i", "o"}).find("command line"), std::string::npos);
  EXPECT_NE(ErrorOf({"i"}).find("command line"), std::string::npos);
  // Each message is one line.
  EXPECT_EQ(ErrorOf({"--count", "11", "i", "o"}).find('\n'), std::string::npos);
}

TEST(CommandLine, HelpAndVersionStopTheRun) {
  testing::internal::CaptureStdout();
  EXPECT_THROW(Parse({"--help"}), HelpShown);
  const std::string help = testing::internal::GetCapturedStdout();
  EXPECT_NE(help.find("--count"), std::string::npos);
  EXPECT_NE(help.find("--returnparameterfile"), std::string::npos);
  testing::internal::CaptureStdout();
  EXPECT_THROW(Parse({"--version"}), HelpShown);
  EXPECT_NE(testing::internal::GetCapturedStdout().find("1.2.3"), std::string::npos);
}

TEST(CommandLine, SlicerOptionsAreRecognised) {
  const Arguments a = Parse({"--processinformationaddress", "0x7ffd1234", "--returnparameterfile",
                             "/tmp/r.txt", "--echo", "i", "o"});
  EXPECT_EQ(a.processInformationAddress, "0x7ffd1234");
  EXPECT_EQ(a.returnParameterFile, "/tmp/r.txt");
  EXPECT_TRUE(a.echo);
}
