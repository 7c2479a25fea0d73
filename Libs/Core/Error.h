#pragma once
// The one error type every stage throws for bad input or impossible work. Its message is the one
// line a user reads on stderr, so it names the input and the problem ("supine CT 'x.nrrd': ...").
#include <stdexcept>
#include <string>

namespace colonmap {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// "what 'path': problem" — the standard shape of a message about one input or output.
inline Error InputError(const std::string& what, const std::string& path, const std::string& problem) {
  return Error(what + " '" + path + "': " + problem);
}

}  // namespace colonmap
