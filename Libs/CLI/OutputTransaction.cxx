#include "CLI/OutputTransaction.h"

#include "Core/Error.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>
#include <system_error>
#include <thread>
#include <unistd.h>

namespace fs = std::filesystem;

namespace colonmap::cli {
namespace {

// Extension as the writers see it, keeping double extensions such as ".mrk.json" or ".nii.gz".
std::string FullExtension(const std::string& filename) {
  const std::string name = fs::path(filename).filename().string();
  for (const char* two : {".mrk.json", ".nii.gz"}) {
    const std::string e(two);
    if (name.size() > e.size() && name.compare(name.size() - e.size(), e.size(), e) == 0) return e;
  }
  return fs::path(name).extension().string();
}

}  // namespace

OutputTransaction::OutputTransaction() {
  // The thread keeps two transactions of one process apart even when they are made at the same
  // tick (a pipeline's two scans run on two threads, writing into the same folders).
  const auto ticks = std::chrono::steady_clock::now().time_since_epoch().count();
  const auto thread = std::hash<std::thread::id>{}(std::this_thread::get_id());
  tag_ = std::to_string(::getpid()) + "-" + std::to_string(ticks % 1000000007) + "-" + std::to_string(thread % 100003);
}

OutputTransaction::~OutputTransaction() {
  if (!committed_) Rollback();
}

void OutputTransaction::PrepareDirectory(const std::string& directory, const std::string& what) {
  if (directory.empty()) throw Error(what + ": no folder given");
  std::error_code ec;
  fs::path dir(directory);
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec)) throw InputError(what, directory, "exists and is not a folder");
  } else {
    // Remember each level we create so that a rollback removes exactly those.
    std::vector<fs::path> missing;
    for (fs::path p = dir; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
      missing.push_back(p);
      if (p == p.parent_path()) break;
    }
    if (!fs::create_directories(dir, ec) && ec)
      throw InputError(what, directory, "cannot create folder (" + ec.message() + ")");
    for (const auto& p : missing) createdDirectories_.push_back(p.string());
  }
  if (::access(dir.c_str(), W_OK) != 0) throw InputError(what, directory, "folder is not writable");
}

std::string OutputTransaction::Stage(const std::string& finalPath, const std::string& what) {
  if (finalPath.empty()) throw Error(what + ": no output file given");
  fs::path final(finalPath);
  fs::path dir = final.parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(what, finalPath, "its folder does not exist");
  if (::access(dir.c_str(), W_OK) != 0) throw InputError(what, finalPath, "its folder is not writable");
  if (fs::is_directory(final, ec)) throw InputError(what, finalPath, "is a folder, not a file");
  const std::string temp = (dir / (".colonmap-tmp-" + tag_ + "-" + std::to_string(counter_++) +
                                   FullExtension(finalPath))).string();
  temps_.push_back(temp);
  finals_.push_back(finalPath);
  isDirectory_.push_back(false);
  return temp;
}

std::string OutputTransaction::StageDirectory(const std::string& finalPath, const std::string& what) {
  if (finalPath.empty()) throw Error(what + ": no output folder given");
  fs::path final(finalPath);
  fs::path dir = final.parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(what, finalPath, "its parent folder does not exist");
  if (fs::exists(final, ec) && !fs::is_directory(final, ec)) throw InputError(what, finalPath, "exists and is not a folder");
  // A name left by an earlier run of the same process id is skipped; a real failure (a full disk,
  // a read-only folder) is said with its reason.
  std::string temp;
  for (int attempt = 0;; ++attempt) {
    temp = (dir / (".colonmap-tmp-" + tag_ + "-" + std::to_string(counter_++))).string();
    if (fs::create_directory(temp, ec)) break;
    if (ec || attempt == 100)
      throw InputError(what, finalPath,
                       "cannot create a temporary folder beside it (" + (ec ? ec.message() : std::string("name taken")) + ")");
  }
  temps_.push_back(temp);
  finals_.push_back(finalPath);
  isDirectory_.push_back(true);
  return temp;
}

void OutputTransaction::Commit() {
  for (std::size_t i = 0; i < temps_.size(); ++i) {
    std::error_code ec;
    if (!fs::exists(temps_[i], ec)) throw Error("output '" + finals_[i] + "' was not written");
  }
  for (std::size_t i = 0; i < temps_.size(); ++i) {
    std::error_code ec;
    if (isDirectory_[i]) fs::remove_all(finals_[i], ec);  // the previous run's folder
    fs::rename(temps_[i], finals_[i], ec);
    if (ec) throw Error("output '" + finals_[i] + "': cannot rename into place (" + ec.message() + ")");
  }
  committed_ = true;
}

std::string OutputTransaction::UserNames(std::string message) const {
  // Longest first: ".colonmap-tmp-T-1" is a prefix of ".colonmap-tmp-T-12".
  std::vector<std::size_t> order(temps_.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return temps_[a].size() > temps_[b].size(); });
  for (std::size_t i : order) {
    for (std::size_t at = message.find(temps_[i]); at != std::string::npos;
         at = message.find(temps_[i], at + finals_[i].size()))
      message.replace(at, temps_[i].size(), finals_[i]);
  }
  return message;
}

void OutputTransaction::Rollback() {
  std::error_code ec;
  for (const auto& t : temps_) fs::remove_all(t, ec);
  // Deepest first; only if empty, so that we never remove what someone else put there.
  for (const auto& d : createdDirectories_) fs::remove(d, ec);
  temps_.clear();
  finals_.clear();
  isDirectory_.clear();
  createdDirectories_.clear();
}

}  // namespace colonmap::cli
