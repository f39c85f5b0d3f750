// Reflective shadow maps as the shaders read them (passes/rsm.cpp, rsm.frag, rsm_rays.comp,
// rsm.glsl).
#ifndef GIQ_RSM_SHARED_H
#define GIQ_RSM_SHARED_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace giq::realtime::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
using uint = uint32_t;
#endif

// Layer kinds.
#define GIQ_RSM_CUBE_FACE 0.0
#define GIQ_RSM_ORTHO 1.0

// Emitter kinds.
#define GIQ_RSM_PUNCTUAL 0.0
#define GIQ_RSM_AREA 1.0

// One RSM layer: a 90-degree cube face around a light (point, spot, area light's
// representative point) or an orthographic window over the whole scene (directional light).
struct GpuRsmLayer {
  mat4 view_proj;      // local frame -> clip, depth in [0, 1]
  mat4 clip_to_world;  // its inverse (inverted in double): the texel rays (rsm_texel.glsl)
  vec4 axes;           // ortho: xyz the direction the light travels, w the window's width (m)
  vec4 params;         // x: kind (GIQ_RSM_*); y: texels per side; z: 1 / flux scale; w: emitter index
};

// What lights the RSM: a punctual light of the scene, or an emissive mesh approximated by a
// cosine-weighted (Lambertian) emitter at its representative point.
struct GpuRsmEmitter {
  vec4 position;   // xyz: light position / representative point; w: kind (GIQ_RSM_PUNCTUAL / _AREA)
  vec4 normal;     // area: xyz unit mean normal of the mesh, w 1 when double-sided; w 2 for a
                   // closed mesh: isotropic, a quarter of `intensity` every way (Cauchy: a
                   // convex body's mean projected area is a quarter of its surface)
  vec4 intensity;  // area: rgb radiant intensity along the normal, sum of radiance x area (W/sr);
                   // punctual: w = index into the scene's lights
  uvec4 layers;    // x: first layer, y: layer count (6 for a cube, 1 for an ortho window);
                   // z, w: triangles [z, z + w) not in its maps (an area light's own; none
                   // for a punctual light)
};

// Push constants of both builders (rsm.vert and rsm.frag; rsm_rays.comp): one layer.
struct RsmLayerPush {
  uint layer;        // index into the GpuRsmLayer buffer
  uint emitter;      // index into the GpuRsmEmitter buffer
  float flux_scale;  // stored value = flux density x scale
  uint size;         // texels per side of the layer; the rays clear the array's texels beyond
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
