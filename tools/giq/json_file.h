#pragma once
// The JSON files the CLI reads back (metrics.json, timings.json, gate.json, stamps, plans).

#include <filesystem>
#include <nlohmann/json.hpp>

namespace giq::cli {

// Throws InputError (the file, what is wrong) when it cannot be opened or is not JSON.
nlohmann::json read_json_file(const std::filesystem::path& file);
// The same, keeping the file's key order (plans and pages written back in that order).
nlohmann::ordered_json read_ordered_json_file(const std::filesystem::path& file);

}  // namespace giq::cli
