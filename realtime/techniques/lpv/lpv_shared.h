// Structures shared by techniques/lpv/lpv.cpp and its shaders.
#ifndef GIQ_LPV_SHARED_H
#define GIQ_LPV_SHARED_H


#ifdef __cplusplus
#include <glm/glm.hpp>
namespace giq::realtime::gpu {
using vec4 = glm::vec4;
using uvec2 = glm::uvec2;
using uint = uint32_t;
#endif

// The grid: cell (i, j, k) covers origin + cell_size * [i, i+1) x [j, j+1) x [k, k+1).
// Storage: cell c = i + res (j + res k); float volumes hold 3 vec4 per cell (2-band SH of the
// radiant intensity, W/sr, for R, G, B), the injection accumulator 12 ints per cell.
struct LpvGrid {
  vec4 origin;            // xyz: the grid's corner; w: cell size (m)
  uint resolution;        // cells per side
  uint rsm_layers;        // layers of the reflective shadow maps
  uint rsm_downsample;    // k: one VPL per k x k RSM block
  uint emitter_count;     // GpuRsmEmitter entries
  float injection_scale;  // fixed point of the injection sums: int units per W/sr
  float intensity;        // multiplier of the indirect light
  float pad0, pad1;
};

struct LpvLookupPush {
  LpvGrid grid;
  uvec2 size;  // the image's width and height
  uvec2 pad;
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
