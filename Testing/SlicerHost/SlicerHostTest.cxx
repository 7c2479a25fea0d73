// Plays 3D Slicer loading each module's shared library into its own process (DESIGN §3.1a):
// dlopen with RTLD_LAZY|RTLD_LOCAL, the two exported symbols, ModuleEntryPoint on a worker
// thread with a ModuleProcessInformation, progress through the callback, Cancel through Abort,
// two runs in one process giving identical outputs, and no process state changed.
#include "Core/TimeLimit.h"
#include "CLI/ModuleDescription.h"
#include "CLI/ProcessInformation.h"
#include "SlicerCommandLine.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <clocale>
#include <csignal>
#include <cstdio>
#include <dlfcn.h>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>

namespace fs = std::filesystem;
using colonmap::cli::ModuleProcessInformation;
using nlohmann::json;

namespace {

using EntryPoint = int (*)(int, char**);

// One row of the host table: Modules/CLI/<Name>/Testing/SlicerHost.json.
struct ModuleCase {
  std::string name;
  json table;
};

// gtest prints test parameters: show the module name, not the object's bytes.
void PrintTo(const ModuleCase& c, std::ostream* os) { *os << c.name; }

std::vector<ModuleCase> Cases() {
  std::vector<ModuleCase> cases;
  std::stringstream list(COLONMAP_HOST_TABLES);  // "Name=path|Name=path"
  std::string item;
  while (std::getline(list, item, '|')) {
    const auto eq = item.find('=');
    std::ifstream in(item.substr(eq + 1));
    cases.push_back({item.substr(0, eq), json::parse(in)});
  }
  return cases;
}

std::string ReadFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string CommandOutput(const std::string& command) {
  std::string out;
  if (FILE* pipe = ::popen(command.c_str(), "r")) {
    char buffer[4096];
    std::size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
    ::pclose(pipe);
  }
  return out;
}

fs::path FreshDir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("colonmap-host-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

class Library {
 public:
  explicit Library(const std::string& name) {
    const std::string path = std::string(COLONMAP_CLI_DIR) + "/lib" + name + "Lib.so";
    handle_ = ::dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (!handle_) throw std::runtime_error(::dlerror());
    xml = static_cast<const char*>(::dlsym(handle_, "XMLModuleDescription"));
    entry = reinterpret_cast<EntryPoint>(::dlsym(handle_, "ModuleEntryPoint"));
  }
  ~Library() { if (handle_) ::dlclose(handle_); }
  const char* xml = nullptr;
  EntryPoint entry = nullptr;

 private:
  void* handle_ = nullptr;
};

struct ProgressLog {
  ModuleProcessInformation* info = nullptr;
  std::vector<float> values;
  std::atomic<int> calls{0};
};

void OnProgress(void* data) {
  auto* log = static_cast<ProgressLog*>(data);
  log->values.push_back(log->info->Progress);
  ++log->calls;
}

// Runs ModuleEntryPoint on a worker thread as Slicer does. `whileRunning` is called on the host
// thread until the run ends.
template <typename F>
int RunInProcess(const Library& lib, const colonmap::cli::ModuleDescription& module,
                 const json& values, const fs::path& out, ModuleProcessInformation& info,
                 ProgressLog& log, F whileRunning) {
  std::map<std::string, std::string> table;
  for (auto& [k, v] : values.items()) {
    std::string s = v.template get<std::string>();
    for (const auto& [key, value] : {std::pair<std::string, std::string>{"{out}", out.string()},
                                     {"{data}", COLONMAP_TEST_DATA}}) {
      const auto at = s.find(key);
      if (at != std::string::npos) s.replace(at, key.size(), value);
    }
    table[k] = s;
  }
  char address[32];
  std::snprintf(address, sizeof address, "%p", static_cast<void*>(&info));
  std::vector<std::string> args = {"slicer:0x55d0c0ffee00", "--processinformationaddress", address};
  if (module.HasReturnParameters()) {
    args.push_back("--returnparameterfile");
    args.push_back((out / "returnparameters.txt").string());
  }
  for (auto& a : colonmap::testing::SlicerArguments(module, table)) args.push_back(a);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  info.ProgressCallbackFunction = OnProgress;
  info.ProgressCallbackClientData = &log;
  log.info = &info;
  std::atomic<bool> done{false};
  int rc = -1;
  std::thread worker([&] {
    rc = lib.entry(static_cast<int>(args.size()), argv.data());
    done = true;
  });
  while (!done) {
    whileRunning();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  worker.join();
  return rc;
}

struct ProcessState {
  std::string cwd, locale;
  mode_t umask = 0;
  std::vector<void (*)(int)> handlers;
  std::ios::fmtflags coutFlags;
  std::streamsize coutPrecision;
  static ProcessState Now() {
    ProcessState s;
    s.cwd = fs::current_path().string();
    s.locale = std::setlocale(LC_ALL, nullptr);
    s.umask = ::umask(022);
    ::umask(s.umask);
    for (int sig : {SIGINT, SIGTERM, SIGSEGV, SIGABRT, SIGPIPE, SIGFPE, SIGCHLD, SIGHUP}) {
      struct sigaction a {};
      ::sigaction(sig, nullptr, &a);
      s.handlers.push_back(a.sa_handler);
    }
    s.coutFlags = std::cout.flags();
    s.coutPrecision = std::cout.precision();
    return s;
  }
  bool operator==(const ProcessState& o) const {
    return cwd == o.cwd && locale == o.locale && umask == o.umask && handlers == o.handlers &&
           coutFlags == o.coutFlags && coutPrecision == o.coutPrecision;
  }
};

std::map<std::string, std::string> Snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = ReadFile(e.path());
  return files;
}

class SlicerHost : public ::testing::TestWithParam<ModuleCase> {};

}  // namespace

TEST_P(SlicerHost, ExportsExactlyTheTwoSymbolsAndTheXml) {
  const ModuleCase& c = GetParam();
  Library lib(c.name);
  ASSERT_NE(lib.xml, nullptr);
  ASSERT_NE(lib.entry, nullptr);
  const std::string exe = std::string(COLONMAP_CLI_DIR) + "/" + c.name;
  EXPECT_EQ(std::string(lib.xml), CommandOutput(exe + " --xml"));
  EXPECT_EQ(std::string(lib.xml), ReadFile(std::string(COLONMAP_CLI_DIR) + "/" + c.name + ".xml"));
  // Only the two symbols are exported (nm lists defined dynamic symbols).
  const std::string symbols = CommandOutput("nm -D --defined-only " + std::string(COLONMAP_CLI_DIR) +
                                            "/lib" + c.name + "Lib.so | awk '{print $3}' | sort");
  EXPECT_EQ(symbols, "ModuleEntryPoint\nXMLModuleDescription\n");
}

TEST_P(SlicerHost, RunsOnAWorkerThreadWithProgressAndKeepsProcessState) {
  const ModuleCase& c = GetParam();
  Library lib(c.name);
  const auto module = colonmap::cli::ParseModuleDescription(lib.xml);
  const ProcessState before = ProcessState::Now();
  std::map<std::string, std::string> outputs[2];
  for (int run = 0; run < 2; ++run) {
    const fs::path out = FreshDir(c.name + "-run" + std::to_string(run));
    ModuleProcessInformation info{};
    ProgressLog log;
    const auto start = std::chrono::steady_clock::now();
    const int rc = RunInProcess(lib, module, c.table["quick"], out, info, log, [] {});
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(rc, 0) << "run " << run;
    std::cout << c.name << ": in-process run " << run << " took " << seconds << " s, "
              << log.calls << " progress callbacks\n";
    if (module.HasReturnParameters()) {
      const std::string returned = ReadFile(out / "returnparameters.txt");
      for (const auto& name : c.table["returns"])
        EXPECT_NE(returned.find(name.get<std::string>() + " = "), std::string::npos) << returned;
    }
    ASSERT_GE(log.values.size(), 3u);
    for (std::size_t i = 1; i < log.values.size(); ++i) EXPECT_GE(log.values[i], log.values[i - 1]);
    EXPECT_FLOAT_EQ(log.values.back(), 1.0f);
    EXPECT_GT(info.ElapsedTime, 0.0);
    for (const auto& name : c.table["outputs"]) EXPECT_TRUE(fs::exists(out / name.get<std::string>())) << name;
    outputs[run] = Snapshot(out);
    fs::remove_all(out);
  }
  // Byte-identical outputs from two runs in one process: no mutable statics.
  ASSERT_EQ(outputs[0].size(), outputs[1].size());
  // Files that record wall-clock times ("timedOutputs") must agree in everything but digits.
  std::set<std::string> timed;
  for (const auto& name : c.table.value("timedOutputs", json::array())) timed.insert(name.get<std::string>());
  const auto masked = [](const std::string& text) {  // each run of digits becomes one '#'
    std::string out;
    for (const char ch : text) {
      const bool digit = ch >= '0' && ch <= '9';
      if (!digit) out += ch;
      else if (out.empty() || out.back() != '#') out += '#';
    }
    return out;
  };
  for (const auto& [name, bytes] : outputs[0]) {
    if (timed.count(name)) EXPECT_TRUE(masked(outputs[1][name]) == masked(bytes)) << name << " differs beyond its times";
    else EXPECT_TRUE(outputs[1][name] == bytes) << name << " differs";
  }
  EXPECT_TRUE(before == ProcessState::Now()) << "the module changed process state";
}

TEST_P(SlicerHost, AbortStopsPromptlyReturnsZeroAndLeavesNothing) {
  const ModuleCase& c = GetParam();
  Library lib(c.name);
  const auto module = colonmap::cli::ParseModuleDescription(lib.xml);
  // Cancel part way, as a user would: once the progress bar has reached this fraction (one or
  // several, each a run of its own), and expect the module back within this many seconds.
  std::vector<float> abortPoints;
  const json at = c.table.value("abortAtProgress", json(0.3f));
  if (at.is_array()) abortPoints = at.get<std::vector<float>>();
  else abortPoints.push_back(at.get<float>());
  const double within = c.table.value("stopsWithinSeconds", 1.0);
  for (const float abortAt : abortPoints) {
    const fs::path out = FreshDir(c.name + "-abort");
    ModuleProcessInformation info{};
    ProgressLog log;
    using Clock = std::chrono::steady_clock;
    Clock::time_point abortedAt;
    const int rc = RunInProcess(lib, module, c.table["long"], out, info, log, [&] {
      if (!info.Abort && info.Progress >= abortAt && info.Progress < 1.0f) {
        info.Abort = 1;
        abortedAt = Clock::now();
      }
    });
    const double afterAbort = std::chrono::duration<double>(Clock::now() - abortedAt).count();
    ASSERT_TRUE(info.Abort) << "the long run ended before the host could cancel it at " << abortAt;
    EXPECT_EQ(rc, 0);
    EXPECT_LT(afterAbort, within * colonmap::kTimeLimitScale)
        << "took " << afterAbort << " s to stop after Abort at progress " << abortAt;
    EXPECT_TRUE(fs::is_empty(out)) << "outputs left behind after Cancel at progress " << abortAt;
    std::cout << c.name << ": stopped " << afterAbort << " s after Abort at progress " << abortAt << "\n";
    fs::remove_all(out);
  }
}

INSTANTIATE_TEST_SUITE_P(Modules, SlicerHost, ::testing::ValuesIn(Cases()),
                         [](const auto& info) { return info.param.name; });
