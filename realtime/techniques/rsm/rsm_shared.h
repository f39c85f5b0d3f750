// Push constants of techniques/rsm/rsm.cpp and rsm_gather.comp.
#ifndef GIQ_RSM_TECHNIQUE_SHARED_H
#define GIQ_RSM_TECHNIQUE_SHARED_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace giq::realtime::gpu {
using uvec2 = glm::uvec2;
using uint = uint32_t;
#endif

struct RsmGatherPush {
  uvec2 size;          // full resolution
  uvec2 low_size;      // the resolution gathered at
  float r_max;         // sampling radius (rsm.cpp's parameter)
  uint samples;        // N
  uint factor;         // downsample factor k
  uint emitter_count;  // GpuRsmEmitter entries
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
