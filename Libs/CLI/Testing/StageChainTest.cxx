// One scan's job of nested modules (ColonSupineProne, issue 22): its steps' share of the job's
// progress, records and notes, two jobs side by side, and the host's Cancel reaching both.
#include "AllTypesXml.h"
#include "CLI/StageChain.h"
#include "Core/Error.h"
#include "Core/RunConcurrently.h"
#include "Core/TimeLimit.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

using namespace colonmap;
using namespace colonmap::cli;

namespace {

const std::vector<std::string> kArgs{"in.nrrd", "out.nrrd", "--title", "job"};

// Reports 0..1 in ten steps, leaves a note and a return value.
void CountingBody(ModuleContext& ctx) {
  for (int i = 0; i <= 10; ++i) {
    ctx.progress.Report(i / 10.0);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ctx.progress.Note("done: " + ctx.args.GetString("title"));
  ctx.SetReturn("total", "7");
}

// Reports every millisecond until it is stopped.
void EndlessBody(ModuleContext& ctx) {
  for (;;) {
    ctx.progress.Report(0.5);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

struct RecordingSink : ProgressSink {
  std::vector<double> values;
  void Report(double f) override { values.push_back(f); }
};

}  // namespace

TEST(StageChain, StepsFillTheirShareOfTheJobAndLeaveRecordsAndNotes) {
  const std::string xml = AllTypesXml();
  RecordingSink sink;
  StageChain chain(sink, {{"first", 1.0}, {"second", 3.0}});
  const auto results = chain.Run("first", "AllTypes", xml.c_str(), &CountingBody, kArgs);
  EXPECT_EQ(results.at("total"), "7");
  EXPECT_NEAR(sink.values.back(), 0.25, 1e-12);  // the first step ends at its weight's share
  for (double v : sink.values) EXPECT_LE(v, 0.25 + 1e-12);
  chain.Run("second", "AllTypes", xml.c_str(), &CountingBody, kArgs);
  EXPECT_NEAR(sink.values.back(), 1.0, 1e-12);
  for (std::size_t i = 1; i < sink.values.size(); ++i) EXPECT_GE(sink.values[i], sink.values[i - 1] - 1e-12);
  ASSERT_EQ(chain.Records().size(), 2u);
  EXPECT_EQ(chain.Records()[1].name, "second");
  EXPECT_EQ(chain.Records()[1].module, "AllTypes");
  EXPECT_GT(chain.Records()[1].seconds, 0.015);  // ten 2 ms sleeps
  EXPECT_GE(chain.Records()[1].threadCpuSeconds, 0.0);
  EXPECT_LT(chain.Records()[1].threadCpuSeconds, chain.Records()[1].seconds);  // sleeping costs no CPU
  const auto notes = chain.TakeNotes();
  EXPECT_EQ(notes, (std::vector<std::string>{"done: job", "done: job"}));
  EXPECT_TRUE(chain.TakeNotes().empty());
}

TEST(StageChain, TwoJobsSideBySideEachKeepTheirOwn) {
  const std::string xml = AllTypesXml();
  RecordingSink sink;  // the host's: only ever called from this thread (RunConcurrently)
  const auto caller = std::this_thread::get_id();
  struct CheckingSink : ProgressSink {
    RecordingSink& inner;
    std::thread::id thread;
    bool otherThread = false;
    CheckingSink(RecordingSink& i, std::thread::id t) : inner(i), thread(t) {}
    void Report(double f) override {
      if (std::this_thread::get_id() != thread) otherThread = true;
      inner.Report(f);
    }
  } host(sink, caller);
  std::vector<StepRecord> records[2];
  std::vector<std::string> notes[2];
  auto job = [&](int k) {
    return [&, k](ProgressSink& s) {
      StageChain chain(s, {{"a", 1.0}, {"b", 1.0}});
      const std::vector<std::string> args{"in.nrrd", "out.nrrd", "--title", k == 0 ? "supine" : "prone"};
      chain.Run("a", "AllTypes", xml.c_str(), &CountingBody, args);
      chain.Run("b", "AllTypes", xml.c_str(), &CountingBody, args);
      records[k] = chain.Records();
      notes[k] = chain.TakeNotes();
    };
  };
  RunConcurrently(job(0), job(1), host);
  EXPECT_FALSE(host.otherThread) << "the host's sink was called from the worker thread";
  EXPECT_NEAR(sink.values.back(), 1.0, 1e-12);
  for (int k = 0; k < 2; ++k) {
    ASSERT_EQ(records[k].size(), 2u);
    EXPECT_EQ(records[k][0].results.at("total"), "7");
  }
  EXPECT_EQ(notes[0], (std::vector<std::string>{"done: supine", "done: supine"}));
  EXPECT_EQ(notes[1], (std::vector<std::string>{"done: prone", "done: prone"}));
}

TEST(StageChain, TheHostsAbortStopsBothJobsPromptly) {
  const std::string xml = AllTypesXml();
  RecordingSink sink;
  std::atomic<bool> abort{false};
  std::atomic<int> started{0};
  auto job = [&](ProgressSink& s) {
    StageChain chain(s, {{"endless", 1.0}}, [&] { return abort.load(); });
    ++started;
    chain.Run("endless", "AllTypes", xml.c_str(), &EndlessBody, kArgs);
  };
  using Clock = std::chrono::steady_clock;
  Clock::time_point abortedAt;
  std::thread host([&] {
    while (started.load() < 2) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    abortedAt = Clock::now();
    abort = true;
  });
  EXPECT_THROW(RunConcurrently(job, job, sink), Cancelled);
  const double after = std::chrono::duration<double>(Clock::now() - abortedAt).count();
  host.join();
  EXPECT_LT(after, 0.2 * kTimeLimitScale) << "both jobs should stop at their next report";
}

TEST(StageChain, AFailingJobStopsTheOtherAndItsErrorIsReported) {
  const std::string xml = AllTypesXml();
  RecordingSink sink;
  auto endless = [&](ProgressSink& s) {
    StageChain chain(s, {{"endless", 1.0}});
    chain.Run("endless", "AllTypes", xml.c_str(), &EndlessBody, kArgs);
  };
  using Clock = std::chrono::steady_clock;
  Clock::time_point failedAt;
  auto failing = [&](ProgressSink&) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    failedAt = Clock::now();
    throw Error("the prone scan cannot be read");
  };
  try {
    RunConcurrently(endless, failing, sink);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "the prone scan cannot be read");  // the worker's, not the stop it caused
  } catch (const Cancelled&) {
    ADD_FAILURE() << "the first job's stop was reported instead of the worker's error";
  }
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - failedAt).count(), 0.2 * kTimeLimitScale);
}
