// Shadow-map layers as the lighting shaders read them (shadow_maps.cpp, shadow.glsl).
#ifndef GIQ_SHADOW_MAPS_SHARED_H
#define GIQ_SHADOW_MAPS_SHARED_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace giq::realtime::gpu {
using vec4 = glm::vec4;
using mat4 = glm::mat4;
using uvec4 = glm::uvec4;
#endif

#define GIQ_SHADOW_CUBE_FACE 0.0
#define GIQ_SHADOW_CASCADE 1.0

// Push constants of shadow_maps.vert: the layer's view-projection, and the vertices it leaves
// out ([skip.x, skip.x + skip.y): ShadowMaps::add_cube).
struct ShadowPush {
  mat4 view_proj;
  uvec4 skip;
};

struct GpuShadowLayer {
  mat4 view_proj;  // local frame -> clip, depth in [0, 1]
  vec4 params;     // x: kind (GIQ_SHADOW_*); y: world size of a texel at distance 1 (cube) or
                   // of a texel (cascade); z: far split distance along the view (cascade);
                   // w: the fraction of the layer's side in use, from its corner (cube)
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
