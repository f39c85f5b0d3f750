#pragma once
// The one way giq reads JSON text: glTF documents, gate configs and plans, metrics.json,
// timings.json, manifests, stamps and technique listings. nlohmann's parser with two checks
// it lacks:
//   - arrays and objects nest at most kMaxJsonDepth deep: deeper input exhausts the stack of
//     whatever walks the document recursively afterwards (tinygltf's conversion of `extras`,
//     a config reader), a crash instead of an error;
//   - no object repeats a key: nlohmann keeps the last value without a word, so a gate bound
//     written as "relmse": 0.01, "relmse": 10 would be checked against 10.
// Both, like text that is not JSON, throw InputError(file, field, message).

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace giq {

inline constexpr int kMaxJsonDepth = 256;

// `file` names the source in errors (a path, or a command whose output this is).
nlohmann::json parse_json(std::string_view text, const std::string& file);
// The same, keeping each object's key order.
nlohmann::ordered_json parse_ordered_json(std::string_view text, const std::string& file);
// The file's text parsed by parse_json / parse_ordered_json; InputError when it cannot be read.
nlohmann::json read_json(const std::filesystem::path& file);
nlohmann::ordered_json read_ordered_json(const std::filesystem::path& file);

}  // namespace giq
