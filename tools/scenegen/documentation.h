#pragma once
// docs/builtin-scenes.md, generated from the same objects the .gltf files are written from, so
// every number in it is the one in the files.

#include <string>
#include <vector>

#include "scenes.h"

namespace giq::scenegen {

std::string documentation(const std::vector<BuiltinScene>& scenes);

}  // namespace giq::scenegen
