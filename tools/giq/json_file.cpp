#include "json_file.h"

#include <fstream>
#include <string>

#include "giq/base/error.h"

namespace giq::cli {

nlohmann::json read_json_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "", "cannot open the file");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file.string(), "", std::string("not valid JSON: ") + e.what());
  }
}

}  // namespace giq::cli
