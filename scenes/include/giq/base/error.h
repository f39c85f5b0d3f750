#pragma once
// The one error type that crosses module boundaries: bad input a user can fix.
// The CLI prints what() as a single line on stderr and exits with code 2.

#include <stdexcept>
#include <string>

namespace giq {

class InputError : public std::runtime_error {
 public:
  // file: the input file (may be empty); field: where in it (a glTF path such as
  // "meshes[2].primitives[0].indices", a channel name, a CLI option); message: what was wrong
  // and what was expected.
  InputError(std::string file, std::string field, const std::string& message);

  const std::string& file() const { return file_; }
  const std::string& field() const { return field_; }
  const std::string& message() const { return message_; }  // what() without file and field

 private:
  std::string file_;
  std::string field_;
  std::string message_;
};

}  // namespace giq
