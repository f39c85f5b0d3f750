// Push constants of techniques/rsm/rsm.cpp and rsm_gather.comp.
#ifndef GIQ_RSM_TECHNIQUE_SHARED_H
#define GIQ_RSM_TECHNIQUE_SHARED_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace giq::realtime::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
#endif

struct RsmGatherPush {
  uvec4 size;    // x, y: full resolution; z, w: the resolution gathered at
  vec4 params;   // x: r_max; y: samples; z: downsample factor k; w: emitters
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
