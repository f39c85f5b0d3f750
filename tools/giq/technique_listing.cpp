#include "technique_listing.h"

#include <fstream>
#include <iterator>
#include <string>

#include "giq/base/error.h"
#include "subprocess.h"

namespace giq::cli {

std::vector<TechniqueParameters> list_techniques(const std::filesystem::path& giq, const std::filesystem::path& log) {
  std::filesystem::create_directories(log.parent_path());
  std::filesystem::remove(log);
  const ProcessResult r = run_process({giq.string(), "realtime", "--list", "--json"}, log);
  if (r.exit_code != 0)
    throw InputError(log.string(), "giq realtime --list --json",
                     "failed (exit " + std::to_string(r.exit_code) + "): " + r.log_tail);
  std::ifstream in(log);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto listed = parse_technique_list(text.substr(text.find('\n') + 1));  // the log's first line is the command
  if (listed.empty()) throw InputError(log.string(), "techniques", "giq realtime --list --json lists no technique");
  return listed;
}

}  // namespace giq::cli
