#include "giq/base/json.h"

#include <fstream>
#include <iterator>
#include <set>
#include <vector>

#include "giq/base/error.h"

namespace giq {
namespace {

// What the parser is inside of: an object (its keys so far, the key being read) or an array.
struct Open {
  bool object = false;
  std::set<std::string> keys;
  std::string key;
};

// Where the parser is, as the fields of InputError name places: "cases[].bounds.relmse"
// (array indices left out, nested arrays as one "[]").
std::string path(const std::vector<Open>& open) {
  std::string p;
  for (size_t i = 0; i < open.size(); ++i) {
    if (!open[i].object) {
      if (i > 0 && (p.size() < 2 || p.compare(p.size() - 2, 2, "[]") != 0)) p += "[]";
      continue;
    }
    if (open[i].key.empty()) continue;
    if (!p.empty()) p += ".";
    p += open[i].key;
  }
  return p;
}

template <class Json>
Json parse(std::string_view text, const std::string& file) {
  std::vector<Open> open;
  auto check = [&](int /*depth*/, typename Json::parse_event_t event, Json& parsed) {
    using E = typename Json::parse_event_t;
    switch (event) {
      case E::object_start:
      case E::array_start:
        if (int(open.size()) >= kMaxJsonDepth)
          throw InputError(file, "JSON",
                           "arrays and objects nest deeper than " + std::to_string(kMaxJsonDepth) + " levels" +
                               (path(open).empty() ? "" : " at " + path(open)) +
                               "; expected a document at most that deep");
        open.push_back({event == E::object_start, {}, {}});
        break;
      case E::object_end:
      case E::array_end:
        open.pop_back();
        break;
      case E::key: {
        Open& o = open.back();
        o.key = parsed.template get<std::string>();
        if (!o.keys.insert(o.key).second)
          throw InputError(file, path(open), "the key \"" + o.key + "\" appears twice in one object; expected each key once");
        break;
      }
      case E::value:
        break;
    }
    return true;
  };
  try {
    return Json::parse(text.begin(), text.end(), check);
  } catch (const nlohmann::json::exception& e) {
    // nlohmann's messages start with "[json.exception.parse_error.101] ".
    std::string what = e.what();
    if (auto p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
    throw InputError(file, "JSON", "not valid JSON: " + what);
  }
}

}  // namespace

nlohmann::json parse_json(std::string_view text, const std::string& file) { return parse<nlohmann::json>(text, file); }

nlohmann::ordered_json parse_ordered_json(std::string_view text, const std::string& file) {
  return parse<nlohmann::ordered_json>(text, file);
}

namespace {

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), "", "cannot open the file");
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError(file.string(), "", "cannot read the file");
  return text;
}

}  // namespace

nlohmann::json read_json(const std::filesystem::path& file) { return parse_json(read_text(file), file.string()); }

nlohmann::ordered_json read_ordered_json(const std::filesystem::path& file) {
  return parse_ordered_json(read_text(file), file.string());
}

}  // namespace giq
