#pragma once
// The built-in scenes: each is built in code by one function and written to
// scenes/<name>.gltf; docs/builtin-scenes.md is generated from the same objects.

#include <string>
#include <vector>

#include "gltf_writer.h"

namespace giq::scenegen {

struct BuiltinScene {
  std::string name;                // file stem
  std::string purpose;             // what the scene is for (one paragraph of the docs)
  std::vector<std::string> notes;  // sources of the numbers and choices made (docs bullets)
  GltfWriter gltf;
};

BuiltinScene make_cornell();
BuiltinScene make_leak();
BuiltinScene make_sunroom();
BuiltinScene make_movinglight();
BuiltinScene make_dynamic();

// How finely the atrium is made: materials (three textures each, of texture_size^2 texels),
// quads round a column and up it, along an arch, across and down a curtain, along a wall.
struct AtriumDetail {
  int materials = 34, texture_size = 2048;
  int column_segments = 192, column_rings = 160, arch_segments = 512;
  int curtain_folds = 240, curtain_rows = 120, panel = 64;
  // The same hall at a few thousand triangles and 16² textures (tests).
  static AtriumDetail small() { return {4, 16, 12, 2, 8, 12, 4, 2}; }
  // The built-in scene (scenes/atrium.gltf): 3,900 triangles and 64² textures, so that the
  // textures are minified in its views at the gate's resolution, as in the large one at 1080p.
  static AtriumDetail builtin() { return {4, 64, 16, 2, 12, 48, 2, 2}; }
};
BuiltinScene make_atrium(const AtriumDetail& detail);

// In the order the documentation lists them.
std::vector<BuiltinScene> all_scenes();

}  // namespace giq::scenegen
