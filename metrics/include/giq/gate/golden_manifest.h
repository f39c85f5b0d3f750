#pragma once
// The golden manifest (<golden_dir>/manifest.json): for every golden reference, the scene it
// was rendered from (path and content hash), the settings (view, frames, resolution, spp or
// target error, seed), what the render achieved (spp, seconds), the giq version and a hash of
// every file. A golden whose scene, settings or files no longer match is stale; the gate
// reports it and never scores against it.
//
// One golden serves every case with the same scene, view and frames; its folder is
// <golden_dir>/<golden_key>/ with frame_NNNN.exr per frame.

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "giq/gate/config.h"

namespace giq::gate {

struct GoldenEntry {
  std::string scene;            // as the config names it, relative to the config's folder
  std::string scene_hash;       // scenes::Scene::content_hash (the glTF and every file it uses)
  nlohmann::json settings;      // golden_settings(case)
  std::optional<uint32_t> spp;  // achieved (the minimum over pixels), when known
  double render_seconds = 0.0;
  std::string giq_version;
  std::map<std::string, std::string> files;  // file name -> file_hash
};

struct Manifest {
  std::map<std::string, GoldenEntry> entries;  // by golden_key
};

// "<scene stem>_<view>_f<A>-<B>", with characters other than [A-Za-z0-9._-] replaced by '_'
// (B = A for a still golden, which a single-frame case of frame A shares).
std::string golden_key(const Case& c);
// {"view", "frames": [A, B], "resolution": [W, H], "spp" or "rel_error", "seed"[, "half"]}
nlohmann::json golden_settings(const Case& c);
// A golden's frame N is frame_file(N) (giq/base/frames.h), as `giq reference --out
// <dir>/frame_####.exr` names it.

// A missing file is an empty manifest; a malformed one throws InputError.
Manifest read_manifest(const std::filesystem::path& file);
void write_manifest(const std::filesystem::path& file, const Manifest& manifest);

// 64-bit FNV-1a of the file's bytes as 16 hex digits (giq::Hasher). Throws InputError when
// the file cannot be read.
std::string file_hash(const std::filesystem::path& file);

struct Freshness {
  enum class State { Fresh, Missing, Stale } state = State::Missing;
  std::string reason;  // for Missing and Stale: what differs, and what to run
};

// Compares the manifest's entry for the case with the scene's current hash, the case's
// settings and the files on disk.
Freshness check_golden(const Manifest& manifest, const std::filesystem::path& golden_dir,
                       const Case& c, const std::string& scene_hash);

// Throws InputError when two cases share a golden key but ask for different settings (the
// one golden could not serve both).
void check_golden_conflicts(const Config& config);

}  // namespace giq::gate
