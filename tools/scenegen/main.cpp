// giq-scenegen: writes the built-in scenes (scenes/*.gltf) and their documentation, or the
// large atrium of the load benchmark (bench/scenes) as one .glb.
// Usage: giq-scenegen <output-dir> [--doc <markdown-file>]
//        giq-scenegen --atrium <file.glb> [--small] [--texture-size N] [--materials N]
// Deterministic: the same bytes on every run, so a test can compare a fresh run with the
// committed files.

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>

#include "documentation.h"
#include "giq/base/atomic_file.h"
#include "giq/base/error.h"
#include "scenes.h"

namespace giq::scenegen {

std::vector<BuiltinScene> all_scenes() {
  std::vector<BuiltinScene> scenes;
  scenes.push_back(make_cornell());
  scenes.push_back(make_leak());
  scenes.push_back(make_sunroom());
  scenes.push_back(make_movinglight());
  scenes.push_back(make_atrium(AtriumDetail::builtin()));
  scenes.push_back(make_dynamic());
  return scenes;
}

}  // namespace giq::scenegen

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  fs::path out_dir, doc, atrium;
  giq::scenegen::AtriumDetail detail;
  auto count = [&](int& i, int lo, int hi) {
    const int v = i + 1 < argc ? std::atoi(argv[++i]) : 0;
    if (v < lo || v > hi) {
      std::fprintf(stderr, "giq-scenegen: %s must be %d to %d\n", argv[i - 1], lo, hi);
      std::exit(2);
    }
    return v;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--doc" && i + 1 < argc) {
      doc = argv[++i];
    } else if (arg == "--atrium" && i + 1 < argc) {
      atrium = argv[++i];
    } else if (arg == "--small") {
      detail = giq::scenegen::AtriumDetail::small();
    } else if (arg == "--texture-size") {
      detail.texture_size = count(i, 1, 8192);
    } else if (arg == "--materials") {
      detail.materials = count(i, 2, 1000);
    } else if (arg == "-h" || arg == "--help") {
      std::printf("usage: giq-scenegen <output-dir> [--doc <markdown-file>]\n"
                  "       giq-scenegen --atrium <file.glb> [--small] [--texture-size N] [--materials N]\n");
      return 0;
    } else if (out_dir.empty() && !arg.starts_with("-")) {
      out_dir = arg;
    } else {
      std::fprintf(stderr, "giq-scenegen: unexpected argument '%s'\n", arg.c_str());
      return 2;
    }
  }
  if (!atrium.empty()) {
    try {
      const auto bytes = giq::scenegen::make_atrium(detail).gltf.dump_glb();
      giq::write_file_atomically(atrium, std::string(bytes.begin(), bytes.end()));
      return 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "giq-scenegen: error: %s\n", e.what());
      return 2;
    }
  }
  if (out_dir.empty()) {
    std::fprintf(stderr, "usage: giq-scenegen <output-dir> [--doc <markdown-file>]\n");
    return 2;
  }
  try {
    const auto scenes = giq::scenegen::all_scenes();
    for (const auto& scene : scenes)
      giq::write_file_atomically(out_dir / (scene.name + ".gltf"), scene.gltf.dump());
    if (!doc.empty()) giq::write_file_atomically(doc, giq::scenegen::documentation(scenes));
  } catch (const giq::InputError& e) {
    std::fprintf(stderr, "giq-scenegen: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "giq-scenegen: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
