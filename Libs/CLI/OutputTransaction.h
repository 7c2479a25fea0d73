#pragma once
// All-or-nothing outputs. Every output is first written under a hidden temporary name in its
// target folder; Commit() renames them all at the very end. Destroying an uncommitted
// transaction (error, Cancel) removes the temporaries and any folder it created, so a failed or
// cancelled run leaves nothing behind. A SIGKILL can leave only hidden ".colonmap-tmp-*" files,
// never a file under an output name.
#include <string>
#include <vector>

namespace colonmap::cli {

class OutputTransaction {
 public:
  OutputTransaction();
  ~OutputTransaction();
  OutputTransaction(const OutputTransaction&) = delete;
  OutputTransaction& operator=(const OutputTransaction&) = delete;

  // Registers an output file and returns the temporary path to write it to. The temporary keeps
  // the final name's extension (writers pick the format from it). Checks the folder is writable.
  // `what` names the output in error messages.
  std::string Stage(const std::string& finalPath, const std::string& what);

  // Registers an output folder filled by nested module runs and returns the hidden temporary
  // folder (created) to fill instead. Commit() replaces a previous folder of that name; Rollback()
  // removes the temporary with everything in it.
  std::string StageDirectory(const std::string& finalPath, const std::string& what);

  // Makes sure an output folder exists (created if needed, removed again on failure if it was
  // created by this transaction). Throws colonmap::Error when it cannot be made or written.
  void PrepareDirectory(const std::string& directory, const std::string& what);

  // Renames every temporary to its final name. Throws colonmap::Error if one cannot be renamed.
  void Commit();
  // Removes all temporaries (and created folders). Also done by the destructor.
  void Rollback();

  const std::vector<std::string>& FinalPaths() const { return finals_; }

  // `message` with every temporary path (and every path inside a temporary folder) replaced by
  // its final name: errors name the user's paths, never our hidden ones (issue 24).
  std::string UserNames(std::string message) const;

 private:
  std::string tag_;
  int counter_ = 0;
  bool committed_ = false;
  std::vector<std::string> temps_, finals_, createdDirectories_;
  std::vector<bool> isDirectory_;
};

}  // namespace colonmap::cli
