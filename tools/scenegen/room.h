#pragma once
// A sealed room beside a thin wall, shared by the scenes that measure leaking (`leak`,
// `dynamic`).

#include <string>

#include "gltf_writer.h"

namespace giq::scenegen {

// Adds a room's floor, ceiling and three outer walls as nodes `<prefix>_floor`,
// `<prefix>_ceiling`, `<prefix>_front_wall` (z = lo), `<prefix>_back_wall` (z = hi) and
// `<prefix>_end_wall`, all facing in; the face `shared` (kXLo or kXHi), where the thin wall
// stands, is left out. Run the room on to the thin wall's middle plane: then its floor,
// ceiling, front and back walls pass under, over and beside the thin wall, so every seam
// between the room and the wall is covered by a surface behind it and no ray finds a crack
// between two quads that merely touch.
void add_room(GltfWriter& gltf, const std::string& prefix, glm::dvec3 lo, glm::dvec3 hi,
              BoxFace shared, int walls, int floor);

// A thin wall across x as a closed box [lo, hi]: its x = lo face as node `lo_face`, its x = hi
// face as `hi_face` (separate nodes, so either side can be a leak region) and its four narrow
// faces as `edges`.
void add_thin_wall(GltfWriter& gltf, glm::dvec3 lo, glm::dvec3 hi, const std::string& lo_face,
                   const std::string& hi_face, const std::string& edges, int material);

}  // namespace giq::scenegen
