#pragma once
// Which folders a module may write into (issue 23). A folder parameter left unset in 3D Slicer
// reaches the module as "." (CTK's directory button returns QDir().path()), and a mistyped one
// can be "/" or the user's home: writing there scatters our files among theirs, and a later
// run's clean-up could touch them. So an output folder must be new, empty, or one that already
// holds ColonMap outputs; "." and a file system root are never accepted.
#include <string>

namespace colonmap::cli {

// Throws colonmap::Error (one line naming `what` and `directory`) when `directory` must not be
// written into: ".", a root, or an existing non-empty folder that does not look like ColonMap's
// (none of the names ColonMap modules always write, in it or in one of its direct subfolders,
// and no ColonMap temporary). A missing folder, or a path that is not a folder, passes (the
// caller creates it, or reports it).
void CheckOutputFolder(const std::string& directory, const std::string& what);

struct ModuleDescription;
class Arguments;
// CheckOutputFolder for every output folder parameter (tag directory, channel output) the user
// gave; RunModule calls it before the module's body, so a refused folder costs nothing and no
// module has to remember it. The error names the parameter by its label.
void CheckOutputFolders(const ModuleDescription& description, const Arguments& args);

}  // namespace colonmap::cli
