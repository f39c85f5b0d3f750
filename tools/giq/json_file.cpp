#include "json_file.h"

#include <fstream>
#include <string>

#include "giq/base/error.h"

namespace giq::cli {

namespace {

template <class Json>
Json read(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "", "cannot open the file");
  try {
    return Json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file.string(), "", std::string("not valid JSON: ") + e.what());
  }
}

}  // namespace

nlohmann::json read_json_file(const std::filesystem::path& file) { return read<nlohmann::json>(file); }

nlohmann::ordered_json read_ordered_json_file(const std::filesystem::path& file) {
  return read<nlohmann::ordered_json>(file);
}

}  // namespace giq::cli
