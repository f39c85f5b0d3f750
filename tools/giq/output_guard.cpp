#include "output_guard.h"

#include <algorithm>

#include "giq/base/error.h"

namespace giq::cli {
namespace fs = std::filesystem;

namespace {

// The path with links and ".." resolved as far as it exists.
fs::path resolved(const fs::path& p) {
  std::error_code ec;
  const fs::path r = fs::weakly_canonical(fs::absolute(p), ec);
  return ec ? fs::absolute(p).lexically_normal() : r;
}

// The first existing ancestor of `p` (its folders, nearest first) that is not a folder.
void check_parents(const fs::path& p, const std::string& option) {
  for (fs::path a = fs::absolute(p).parent_path(); !a.empty(); a = a.parent_path()) {
    std::error_code ec;
    const fs::file_status s = fs::status(a, ec);
    if (fs::exists(s) && !fs::is_directory(s))
      throw InputError(a.string(), option, "is a file where a folder of " + p.string() + " would be");
    if (a == a.parent_path()) break;
  }
}

}  // namespace

bool path_inside(const fs::path& p, const fs::path& folder) {
  const fs::path a = resolved(p), b = resolved(folder);
  return std::mismatch(b.begin(), b.end(), a.begin(), a.end()).first == b.end();
}

void check_output_file(const fs::path& out, const std::vector<fs::path>& inputs, const std::string& option) {
  if (fs::is_directory(out)) throw InputError(out.string(), option, "is a folder; expected a file path to write");
  check_parents(out, option);
  for (const fs::path& in : inputs)
    if (!in.empty() && resolved(in) == resolved(out))
      throw InputError(out.string(), option, "is also an input (" + in.string() + "); it would be overwritten");
}

void check_output_folder(const fs::path& out, const std::vector<fs::path>& inputs, const std::string& option) {
  std::error_code ec;
  const fs::file_status s = fs::status(out, ec);
  if (fs::exists(s) && !fs::is_directory(s))
    throw InputError(out.string(), option, "is a file; expected a folder to write into");
  check_parents(out, option);
  for (const fs::path& in : inputs)
    if (!in.empty() && path_inside(in, out))
      throw InputError(out.string(), option,
                       "holds the input " + in.string() + ", which this command's files could replace; write elsewhere");
}

}  // namespace giq::cli
