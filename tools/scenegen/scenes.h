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

// In the order the documentation lists them.
std::vector<BuiltinScene> all_scenes();

}  // namespace giq::scenegen
