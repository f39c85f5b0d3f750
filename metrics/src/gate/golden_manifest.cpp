#include "giq/gate/golden_manifest.h"

#include <cctype>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "giq/base/atomic_file.h"
#include "giq/base/error.h"
#include "giq/base/json.h"
#include "giq/base/frames.h"
#include "giq/base/hash.h"

namespace giq::gate {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string sanitize(const std::string& s) {
  std::string out;
  for (char c : s)
    out +=
        std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_' ? c : '_';
  return out;
}

}  // namespace

std::string golden_key(const Case& c) {
  // A camera's golden is named by a hash of the camera as given, so that two cameras of one
  // scene get two goldens.
  const std::string view = c.camera.empty() ? c.view : "camera-" + Hasher().add(c.camera).hex().substr(0, 8);
  return sanitize(c.scene.stem().string() + "_" + view + "_f" + std::to_string(c.first_frame) + "-" +
                  std::to_string(c.golden_last_frame()));
}

json golden_settings(const Case& c) {
  json s = {{"view", c.view},
            {"frames", {c.first_frame, c.golden_last_frame()}},
            {"resolution", {c.width, c.height}},
            {"seed", c.golden.seed}};
  if (c.golden.spp) s["spp"] = *c.golden.spp;
  if (c.golden.rel_error) s["rel_error"] = *c.golden.rel_error;
  // Only when set, so the manifests of float32 goldens written before the option stay fresh.
  if (c.golden.half) s["half"] = true;
  if (c.golden.sampler != "independent") s["sampler"] = c.golden.sampler;
  if (!c.camera.empty()) s["camera"] = c.camera;
  return s;
}

Manifest read_manifest(const fs::path& file) {
  Manifest m;
  if (!fs::exists(file)) return m;
  try {
    const json j = read_json(file);
    if (j.at("version") != 1)
      throw InputError(file.string(), "version", j["version"].dump() + "; expected 1");
    for (const auto& [key, e] : j.at("goldens").items()) {
      GoldenEntry g;
      g.scene = e.at("scene").get<std::string>();
      g.scene_hash = e.at("scene_hash").get<std::string>();
      g.settings = e.at("settings");
      if (e.contains("spp") && !e["spp"].is_null()) g.spp = e["spp"].get<uint32_t>();
      g.render_seconds = e.value("render_seconds", 0.0);
      g.giq_version = e.value("giq_version", "");
      for (const auto& [name, h] : e.at("files").items()) g.files[name] = h.get<std::string>();
      m.entries[key] = std::move(g);
    }
  } catch (const json::exception& e) {
    throw InputError(file.string(), "", std::string("not a golden manifest: ") + e.what());
  }
  return m;
}

void write_manifest(const fs::path& file, const Manifest& m) {
  json goldens = json::object();
  for (const auto& [key, g] : m.entries) {
    json files = json::object();
    for (const auto& [name, h] : g.files) files[name] = h;
    goldens[key] = {{"scene", g.scene},
                    {"scene_hash", g.scene_hash},
                    {"settings", g.settings},
                    {"spp", g.spp ? json(*g.spp) : json(nullptr)},
                    {"render_seconds", g.render_seconds},
                    {"giq_version", g.giq_version},
                    {"files", files}};
  }
  const json j = {
      {"version", 1},
      {"note", "written by giq golden update; a golden that disagrees with this file is stale"},
      {"goldens", goldens}};
  write_file_atomically(file, j.dump(2) + "\n");
}

std::string file_hash(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), "", "cannot read the file to hash it");
  Hasher h;
  char buf[1 << 16];
  while (in) {
    in.read(buf, sizeof buf);
    if (in.gcount() > 0) h.add(buf, size_t(in.gcount()));
  }
  return h.hex();
}

Freshness check_golden(const Manifest& manifest, const fs::path& golden_dir, const Case& c,
                       const std::string& scene_hash) {
  const std::string key = golden_key(c);
  Freshness f;
  const auto it = manifest.entries.find(key);
  if (it == manifest.entries.end()) {
    f.reason = "golden " + key + " is missing from " + (golden_dir / "manifest.json").string() +
               "; run giq golden update";
    return f;
  }
  const GoldenEntry& g = it->second;
  f.state = Freshness::State::Stale;
  if (g.scene_hash != scene_hash) {
    f.reason = "golden " + key + " is stale: the scene changed (hash " + g.scene_hash +
               " in the manifest, " + scene_hash + " now); run giq golden update";
    return f;
  }
  const json want = golden_settings(c);
  if (g.settings != want) {
    f.reason = "golden " + key + " is stale: rendered with " + g.settings.dump() +
               ", the config asks for " + want.dump() + "; run giq golden update";
    return f;
  }
  for (int frame = c.first_frame; frame <= c.golden_last_frame(); ++frame) {
    const std::string name = frame_file(frame);
    const fs::path p = golden_dir / key / name;
    const auto h = g.files.find(name);
    if (h == g.files.end() || !fs::exists(p)) {
      f.state = Freshness::State::Missing;
      f.reason = "golden file " + p.string() + " is missing; run giq golden update";
      return f;
    }
    if (file_hash(p) != h->second) {
      f.reason = "golden file " + p.string() +
                 " was modified after giq golden update wrote it (hash " + file_hash(p) +
                 ", manifest " + h->second + "); run giq golden update";
      return f;
    }
  }
  f.state = Freshness::State::Fresh;
  f.reason.clear();
  return f;
}

void check_golden_conflicts(const Config& config) {
  std::map<std::string, const Case*> seen;
  for (const Case& c : config.cases) {
    const auto [it, inserted] = seen.emplace(golden_key(c), &c);
    if (!inserted && golden_settings(*it->second) != golden_settings(c))
      throw InputError(config.file.string(), "cases." + c.name,
                       "shares golden " + it->first + " with case " + it->second->name +
                           " but asks for other settings (" + golden_settings(c).dump() + " vs " +
                           golden_settings(*it->second).dump() +
                           "); give both the same resolution and golden settings");
  }
}

}  // namespace giq::gate
