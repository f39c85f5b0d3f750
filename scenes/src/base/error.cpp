#include "giq/base/error.h"

namespace giq {
namespace {

std::string compose(const std::string& file, const std::string& field, const std::string& message) {
  std::string s;
  if (!file.empty()) s += file + ": ";
  if (!field.empty()) s += field + ": ";
  s += message;
  // One line on stderr: a message never spans lines, whatever its parts contained.
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

}  // namespace

InputError::InputError(std::string file, std::string field, const std::string& message)
    : std::runtime_error(compose(file, field, message)),
      file_(std::move(file)),
      field_(std::move(field)),
      message_(message) {}

}  // namespace giq
