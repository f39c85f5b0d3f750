// Structures shared by techniques/lpv/lpv.cpp and its shaders.
#ifndef GIQ_LPV_SHARED_H
#define GIQ_LPV_SHARED_H


#ifdef __cplusplus
#include <glm/glm.hpp>
namespace giq::realtime::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
#endif

// The grid: cell (i, j, k) covers origin + cell_size * [i, i+1) x [j, j+1) x [k, k+1).
// Storage: cell c = i + res (j + res k); float volumes hold 3 vec4 per cell (2-band SH of the
// radiant intensity, W/sr, for R, G, B), the injection accumulator 12 ints per cell.
struct LpvGrid {
  vec4 origin;  // xyz: the grid's corner; w: cell size (m)
  uvec4 size;   // x: cells per side; y: layers of the RSM; z: RSM downsample factor; w: emitters
  vec4 params;  // x: fixed-point scale of injection (int units per W/sr); y: intensity
};

struct LpvLookupPush {
  LpvGrid grid;
  uvec4 size;  // x, y: image size
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
