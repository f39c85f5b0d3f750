// Shadow-map layers as the lighting shaders read them (shadow_maps.cpp, shadow.glsl), and the
// builders' push constants.
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

// Push constants of shadow_maps.vert: the layer's view-projection, and what it leaves out
// (ShadowMaps::add_cube): the vertices [skip.x, skip.x + skip.y), which are the triangles
// [skip.z, skip.z + skip.w).
struct ShadowPush {
  mat4 view_proj;
  uvec4 skip;
};

// Push constants of shadow_maps_rays.comp: one layer.
struct ShadowRayPush {
  uvec4 skip;        // as ShadowPush's; the rays leave out the triangles
  uint layer;        // index into the GpuShadowLayer buffer
  uint size;         // texels per side in use, from the layer's corner
  float slope_bias;  // the rasteriser's slope-scaled depth bias factor
  uint pad;
};

struct GpuShadowLayer {
  mat4 view_proj;      // local frame -> clip, depth in [0, 1]
  mat4 clip_to_world;  // its inverse (inverted in double): the texel rays (shaders/texel_ray.glsl)
  vec4 params;         // x: kind (GIQ_SHADOW_*); y: world size of a texel at distance 1 (cube) or
                       // of a texel (cascade); z: far split distance along the view (cascade);
                       // w: the fraction of the layer's side in use, from its corner (cube)
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
