#pragma once
// A cube of `resolution` cells per side fitted around a scene's bounds: the bounds' largest
// side spans resolution - 2 cells, centred, so a cell of margin on each side keeps surfaces on
// the bounds (and offsets of half a cell along their normals) inside the cube. `lpv`'s
// propagation volume and `vct`'s voxels are fitted this way.

#include <cstdint>
#include <glm/glm.hpp>

#include "giq/scenes/scene.h"

namespace giq::realtime {

struct CubeGrid {
  glm::vec3 origin;  // the cube's min corner
  float cell;        // edge length of a cell
};

// An empty scene gets a unit cube around the origin.
inline CubeGrid fit_cube_grid(const scenes::Bounds& bounds, uint32_t resolution) {
  const float side = bounds.empty() ? 1.0f : bounds.largest_side();
  const float cell = side / float(resolution > 2 ? resolution - 2 : 1);
  return {bounds.centre() - 0.5f * cell * float(resolution), cell};
}

}  // namespace giq::realtime
