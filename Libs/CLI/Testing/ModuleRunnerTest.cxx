// The run wrapper: --xml, --echo, return parameters, errors, Cancel, all-or-nothing outputs.
#include "AllTypesXml.h"
#include "Core/Testing/FreshTempDir.h"
#include "CLI/ModuleRunner.h"
#include "CLI/OutputTransaction.h"
#include "Core/Error.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace colonmap;
using namespace colonmap::cli;

namespace {

fs::path TempDir(const std::string& name) { return colonmap::FreshTempDir("runner", name); }

std::string ReadFile(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

int RunAllTypes(std::vector<std::string> args, ModuleBody body) {
  const std::string xml = AllTypesXml();
  args.insert(args.begin(), "AllTypes");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  return RunModule("AllTypes", xml.c_str(), static_cast<int>(argv.size()), argv.data(), body);
}

// Writes the output volume's path as text, in two stages, and returns a value.
void WritingBody(ModuleContext& ctx) {
  const std::string temp = ctx.outputs.Stage(ctx.args.GetString("outputVolume"), "output volume");
  ctx.progress.StartStage("first");
  ctx.progress.Report(0.5);
  std::ofstream(temp) << "count=" << ctx.args.GetInt("count");
  ctx.progress.EndStage();
  ctx.progress.StartStage("second");
  ctx.progress.EndStage();
  ctx.SetReturn("total", "42.5");
}

void FailingBody(ModuleContext& ctx) {
  const std::string temp = ctx.outputs.Stage(ctx.args.GetString("outputVolume"), "output volume");
  std::ofstream(temp) << "partial";
  throw InputError("input volume", ctx.args.GetString("inputVolume"), "holds no colon");
}

}  // namespace

TEST(ModuleRunner, XmlFlagPrintsTheDescriptionExactly) {
  testing::internal::CaptureStdout();
  EXPECT_EQ(RunAllTypes({"--xml"}, WritingBody), 0);
  EXPECT_EQ(testing::internal::GetCapturedStdout(), AllTypesXml());
}

TEST(ModuleRunner, WritesOutputsProgressTagsAndReturnParameters) {
  const fs::path dir = TempDir("ok");
  const fs::path out = dir / "out.nrrd", ret = dir / "ret.txt";
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  const int rc = RunAllTypes({"--returnparameterfile", ret.string(), "--count", "5", "in.nrrd", out.string()}, WritingBody);
  const std::string stdoutText = testing::internal::GetCapturedStdout();
  const std::string stderrText = testing::internal::GetCapturedStderr();
  EXPECT_EQ(rc, 0);
  EXPECT_EQ(stderrText, "");
  EXPECT_EQ(ReadFile(out), "count=5");
  EXPECT_EQ(ReadFile(ret), "total = 42.5\n");
  EXPECT_NE(stdoutText.find("<filter-start><filter-name>first</filter-name>"), std::string::npos);
  EXPECT_NE(stdoutText.find("<filter-progress>0.5000</filter-progress>"), std::string::npos);
  EXPECT_NE(stdoutText.find("<filter-end><filter-name>second</filter-name><filter-time>"), std::string::npos);
  // Only the two outputs are left: no temporaries.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
  fs::remove_all(dir);
}

TEST(ModuleRunner, EchoPrintsParsedValues) {
  const fs::path dir = TempDir("echo");
  testing::internal::CaptureStdout();
  EXPECT_EQ(RunAllTypes({"--echo", "--sigma", "3", "in.nrrd", (dir / "o.nrrd").string()}, WritingBody), 0);
  const std::string text = testing::internal::GetCapturedStdout();
  EXPECT_NE(text.find("sigma = 3\n"), std::string::npos);
  EXPECT_NE(text.find("count = 3\n"), std::string::npos);
  EXPECT_NE(text.find("inputVolume = in.nrrd\n"), std::string::npos);
  fs::remove_all(dir);
}

TEST(ModuleRunner, FailureGivesOneStderrLineNonZeroExitAndNoOutput) {
  const fs::path dir = TempDir("fail");
  testing::internal::CaptureStderr();
  const int rc = RunAllTypes({"empty.nrrd", (dir / "out.nrrd").string()}, FailingBody);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(rc, 0);
  EXPECT_EQ(err, "AllTypes: error: input volume 'empty.nrrd': holds no colon\n");
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

TEST(ModuleRunner, BadCommandLineFailsWithoutRunning) {
  testing::internal::CaptureStderr();
  EXPECT_EQ(RunAllTypes({"--count", "99", "in", "out"}, FailingBody), 1);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("above the maximum"), std::string::npos);
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1);
}

TEST(ModuleRunner, UnwritableOutputFolderIsReported) {
  testing::internal::CaptureStderr();
  EXPECT_EQ(RunAllTypes({"in.nrrd", "/nonexistent-folder/out.nrrd"}, WritingBody), 1);
  EXPECT_NE(testing::internal::GetCapturedStderr().find("'/nonexistent-folder/out.nrrd': its folder does not exist"),
            std::string::npos);
}

TEST(OutputTransaction, RollbackRemovesTemporariesAndCreatedFolders) {
  const fs::path dir = TempDir("tx");
  {
    OutputTransaction tx;
    tx.PrepareDirectory((dir / "a" / "b").string(), "output folder");
    EXPECT_TRUE(fs::is_directory(dir / "a" / "b"));
    const std::string temp = tx.Stage((dir / "a" / "b" / "x.mrk.json").string(), "x");
    EXPECT_NE(temp.find(".mrk.json"), std::string::npos);
    std::ofstream(temp) << "x";
  }
  EXPECT_TRUE(fs::is_empty(dir));
  {
    OutputTransaction tx;
    const std::string temp = tx.Stage((dir / "y.txt").string(), "y");
    std::ofstream(temp) << "y";
    EXPECT_FALSE(fs::exists(dir / "y.txt"));
    tx.Commit();
  }
  EXPECT_EQ(ReadFile(dir / "y.txt"), "y");
  {
    OutputTransaction tx;
    tx.Stage((dir / "never.txt").string(), "z");
    EXPECT_THROW(tx.Commit(), Error);  // an output that was not written is an error
  }
  fs::remove_all(dir);
}

// Errors name the user's paths, never our hidden temporaries, also inside a staged folder (issue 24).
TEST(OutputTransaction, UserNamesReplaceTemporaries) {
  const fs::path dir = TempDir("names");
  OutputTransaction tx;
  std::vector<std::string> temps;
  for (int i = 0; i < 12; ++i) temps.push_back(tx.Stage((dir / ("f" + std::to_string(i) + ".nrrd")).string(), "f"));
  const std::string folder = tx.StageDirectory((dir / "stage").string(), "stage");
  EXPECT_EQ(tx.UserNames("a '" + temps[1] + "' b '" + temps[11] + "' c"),
            "a '" + (dir / "f1.nrrd").string() + "' b '" + (dir / "f11.nrrd").string() + "' c");
  EXPECT_EQ(tx.UserNames("x '" + folder + "/sub/y.vtp'"), "x '" + (dir / "stage").string() + "/sub/y.vtp'");
  tx.Rollback();
  fs::remove_all(dir);
}

// A temporary folder name already taken (a process of the same id, killed) is skipped; a folder
// that cannot be made is said with the system's reason (CI once ran out of disk and said none).
TEST(OutputTransaction, StageDirectorySkipsATakenNameAndSaysWhyItCannotCreate) {
  const fs::path dir = TempDir("taken");
  OutputTransaction tx;
  const std::string file = tx.Stage((dir / "noextension").string(), "f");  // ".colonmap-tmp-TAG-0"
  const std::string taken = file.substr(0, file.size() - 1) + "1";
  fs::create_directory(taken);
  const std::string folder = tx.StageDirectory((dir / "stage").string(), "stage");
  EXPECT_NE(folder, taken);
  EXPECT_TRUE(fs::is_directory(folder));
  tx.Rollback();
  fs::remove_all(dir);
  try {
    tx.StageDirectory("/proc/colonmap-stage", "stage folder");
    ADD_FAILURE() << "a folder in /proc was staged";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("'/proc/colonmap-stage': cannot create a temporary folder beside it ("), std::string::npos) << m;
    EXPECT_EQ(m.find("name taken"), std::string::npos) << m;
  }
}

TEST(Progress, InProcessStructGetsMonotoneProgressCallbacksAndAbort) {
  ModuleProcessInformation info{};
  struct Log { std::vector<float> values; ModuleProcessInformation* info; } log{{}, &info};
  info.ProgressCallbackClientData = &log;
  info.ProgressCallbackFunction = [](void* data) {
    auto* l = static_cast<Log*>(data);
    l->values.push_back(l->info->Progress);
  };
  Progress progress("Test", Progress::Style::Silent, &info, stdout);
  progress.Plan({{"a", 1.0}, {"b", 3.0}});
  progress.StartStage("a");
  for (int i = 0; i <= 10; ++i) progress.Report(i / 10.0);
  progress.EndStage();
  progress.StartStage("b");
  progress.Report(0.5);
  EXPECT_STREQ(info.ProgressMessage, "b");
  EXPECT_NEAR(info.Progress, 0.25 + 0.75 * 0.5, 1e-6);
  progress.EndStage();
  progress.Finish();
  ASSERT_GE(log.values.size(), 5u);
  for (std::size_t i = 1; i < log.values.size(); ++i) EXPECT_GE(log.values[i], log.values[i - 1]);
  EXPECT_FLOAT_EQ(log.values.back(), 1.0f);
  info.Abort = 1;
  EXPECT_THROW(progress.Report(0.1), Cancelled);
  EXPECT_THROW(progress.StartStage("c"), Cancelled);  // a new stage polls Cancel too
}

TEST(Progress, AddressParsing) {
  ModuleProcessInformation info{};
  char text[32];
  std::snprintf(text, sizeof text, "%p", static_cast<void*>(&info));
  EXPECT_EQ(ProcessInformationFromAddress(text), &info);
  EXPECT_EQ(ProcessInformationFromAddress(""), nullptr);
  EXPECT_EQ(ProcessInformationFromAddress("zz"), nullptr);
}

TEST(Progress, TerminalStyleIsReadableWithStageTimes) {
  std::FILE* out = std::tmpfile();
  Progress progress("Demo", Progress::Style::Terminal, nullptr, out);
  progress.StartStage("Segmentation", "lumen");
  progress.Report(0.5);
  progress.EndStage();
  progress.Finish();
  std::rewind(out);
  char buffer[512] = {};
  const std::size_t n = std::fread(buffer, 1, sizeof buffer - 1, out);
  std::fclose(out);
  const std::string text(buffer, n);
  EXPECT_NE(text.find("Demo: Segmentation - lumen\n"), std::string::npos) << text;
  EXPECT_NE(text.find("Demo: Segmentation done in "), std::string::npos) << text;
  EXPECT_EQ(text.find("<filter"), std::string::npos) << text;
  ASSERT_EQ(progress.StageTimes().size(), 1u);
  EXPECT_EQ(progress.StageTimes()[0].first, "Segmentation");
}
