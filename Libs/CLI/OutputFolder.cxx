#include "CLI/OutputFolder.h"

#include "CLI/Arguments.h"
#include "CLI/ModuleDescription.h"

#include "Core/Error.h"

#include <array>
#include <cctype>
#include <filesystem>
#include <string_view>
#include <system_error>

namespace fs = std::filesystem;

namespace colonmap::cli {
namespace {

// Files that one of our modules always writes (DESIGN §2.0): any one of them marks a folder as
// ColonMap's. The record of each folder-writing module, and the pipeline's own outputs.
constexpr std::array<std::string_view, 12> kOurNames = {
    "truth.json",        // ColonPhantom
    "supine.nrrd",       "prone.nrrd",
    "landmarks.json",    // ColonLandmarks
    "colon_open.vtp",
    "flattening.json",   // ColonFlattening
    "registration.json", // ColonRegistration
    "registration.vtp",
    "flatviews.json",    // ColonFlatViews
    "cameras.json",      // ColonEndoluminalViews
    "summary.json",      // ColonSupineProne
    "report.html"};

// What a killed run leaves (OutputTransaction): hidden temporaries.
constexpr std::string_view kTemporaryPrefix = ".colonmap-tmp-";

bool IsOurEntry(const fs::path& entry) {
  const std::string name = entry.filename().string();
  if (name.compare(0, kTemporaryPrefix.size(), kTemporaryPrefix) == 0) return true;
  for (std::string_view ours : kOurNames)
    if (name == ours) return true;
  return false;
}

// Ours when an entry is ours, or an entry of a direct subfolder (ColonSupineProne's output
// folder holding a ColonPhantom folder, a cohort case folder holding stage folders).
bool LooksLikeOurs(const fs::path& dir, std::string* firstForeign) {
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    if (IsOurEntry(e.path())) return true;
    if (firstForeign->empty()) *firstForeign = e.path().filename().string();
    std::error_code sub;
    if (!e.is_directory(sub)) continue;
    for (const fs::directory_entry& inner : fs::directory_iterator(e.path(), sub))
      if (IsOurEntry(inner.path())) return true;
  }
  return false;
}

}  // namespace

void CheckOutputFolder(const std::string& directory, const std::string& what) {
  if (directory.empty()) throw Error(what + ": no folder given");
  const fs::path dir(directory);
  if (dir.lexically_normal() == "." || dir.lexically_normal() == "./")
    throw InputError(what, directory,
                     "the current folder is not accepted as an output folder (3D Slicer passes '.' for a folder left "
                     "unset): choose a folder, by its name or path");
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(fs::absolute(dir, ec), ec);
  if (!ec && resolved == resolved.root_path())
    throw InputError(what, directory, "is the root of the file system: choose a folder of its own");
  if (!fs::is_directory(dir, ec) || fs::is_empty(dir, ec)) return;
  std::string foreign;
  if (!LooksLikeOurs(dir, &foreign))
    throw InputError(what, directory,
                     "is not empty and holds no ColonMap output (e.g. '" + foreign +
                         "'): choose a new or empty folder, or one a ColonMap module wrote");
}

void CheckOutputFolders(const ModuleDescription& description, const Arguments& args) {
  for (const ParameterDescription* p : description.Parameters()) {
    if (p->tag != "directory" || p->channel != "output") continue;
    const std::string value = args.GetString(p->name);
    if (value.empty()) continue;
    std::string what = p->label.empty() ? p->name : p->label;  // "Output folder" -> "output folder ..."
    const std::string mark = " (required)";                      // the label's mark, not the message's
    if (what.size() > mark.size() && what.compare(what.size() - mark.size(), mark.size(), mark) == 0)
      what.erase(what.size() - mark.size());
    what[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(what[0])));
    CheckOutputFolder(value, what);
  }
}

}  // namespace colonmap::cli
