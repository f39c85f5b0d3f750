#include "json_file.h"

#include <fstream>
#include <iterator>
#include <string>

#include "giq/base/error.h"
#include "giq/base/json.h"

namespace giq::cli {

namespace {

std::string slurp(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), "", "cannot open the file");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

nlohmann::json read_json_file(const std::filesystem::path& file) { return read_json(file.string()); }

nlohmann::ordered_json read_ordered_json_file(const std::filesystem::path& file) {
  return parse_ordered_json(slurp(file), file.string());
}

}  // namespace giq::cli
