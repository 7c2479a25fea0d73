// Which output folders a module accepts (issue 23): never ".", never a root, never someone
// else's non-empty folder; new, empty and ColonMap folders are fine.
#include "CLI/OutputFolder.h"
#include "Core/Error.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace colonmap;
using namespace colonmap::cli;

namespace {

struct Folder {
  fs::path path = fs::temp_directory_path() / ("colonmap-outfolder-" + std::to_string(::getpid()));
  Folder() {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~Folder() { fs::remove_all(path); }
  void Touch(const fs::path& relative) const {
    fs::create_directories((path / relative).parent_path());
    std::ofstream(path / relative) << "x";
  }
};

// The one-line message, or "" when the folder is accepted.
std::string Refusal(const std::string& directory) {
  try {
    CheckOutputFolder(directory, "output folder");
    return "";
  } catch (const Error& e) {
    return e.what();
  }
}

}  // namespace

TEST(OutputFolder, CurrentFolderAndRootAreRefused) {
  for (const char* dot : {".", "./", "a/.."}) {
    const std::string m = Refusal(dot);
    EXPECT_NE(m.find(std::string("output folder '") + dot + "'"), std::string::npos) << m;
    EXPECT_NE(m.find("current folder"), std::string::npos) << m;
  }
  for (const char* root : {"/", "//", "/tmp/.."}) {
    const std::string m = Refusal(root);
    EXPECT_NE(m.find("root of the file system"), std::string::npos) << root << ": " << m;
  }
}

TEST(OutputFolder, NewEmptyAndOurFoldersAreAccepted) {
  Folder f;
  EXPECT_EQ(Refusal((f.path / "new" / "deeper").string()), "");
  EXPECT_EQ(Refusal(f.path.string()), "");  // empty
  f.Touch("registration.json");
  f.Touch("notes.txt");  // a user's note beside our outputs does not matter
  EXPECT_EQ(Refusal(f.path.string()), "");
}

TEST(OutputFolder, OurOutputsOneLevelDownOrATemporaryCount) {
  Folder f;
  f.Touch("phantom/truth.json");  // ColonSupineProne's folder holding the phantom it was run on
  EXPECT_EQ(Refusal(f.path.string()), "");
  fs::remove_all(f.path / "phantom");
  f.Touch(".colonmap-tmp-123-4-0.vtp");  // what a killed run leaves
  EXPECT_EQ(Refusal(f.path.string()), "");
  fs::remove_all(f.path);
  f.Touch("a/b/summary.json");  // two levels down is not looked at
  EXPECT_NE(Refusal(f.path.string()), "");
}

TEST(OutputFolder, SomeoneElsesFolderIsRefusedByName) {
  Folder f;
  f.Touch("thesis.tex");
  const std::string m = Refusal(f.path.string());
  EXPECT_NE(m.find("output folder '" + f.path.string() + "': is not empty and holds no ColonMap output (e.g. 'thesis.tex')"),
            std::string::npos)
      << m;
  EXPECT_EQ(m.find('\n'), std::string::npos);
  EXPECT_TRUE(fs::exists(f.path / "thesis.tex"));
}

TEST(OutputFolder, AFileIsLeftToTheCaller) {
  Folder f;
  f.Touch("file.txt");
  EXPECT_EQ(Refusal((f.path / "file.txt").string()), "");  // PrepareDirectory says "is not a folder"
}
