// Structures shared by passes/direct_light.cpp and direct_light.comp.
#ifndef GIQ_DIRECT_LIGHT_SHARED_H
#define GIQ_DIRECT_LIGHT_SHARED_H

#include "shaders/camera_shared.h"

#ifdef __cplusplus
namespace giq::realtime::gpu {
using uvec2 = glm::uvec2;
using uvec4 = glm::uvec4;
#endif

struct DirectPush {
  GpuCamera camera;
  vec4 environment;       // rgb constant environment radiance, w its map's texture or -1 (shaders/environment.glsl)
  uvec2 size;             // the image's width and height
  float normal_offset;    // receiver offset along its normal, in shadow-map texels
  uint pcf_radius;        // PCF kernel radius in texels
  uint light_count;       // punctual lights
  uint area_light_count;  // emissive meshes
  uint area_shadow_rays;  // 0: area lights shadowed by their cube maps; else rays a pixel to each
  // A cluster of particles lights as one where its box is smaller than this times its
  // distance (direct_light.comp, particle_tree_light); 0: every particle alone.
  float particle_cut;
  uint pad0, pad1, pad2, pad3;
};

// An emissive mesh as one area light: its triangles are integrated exactly, a stage of glowing
// particles particle by particle (shaders/octahedron_irradiance.glsl), unshadowed; the light
// is shadowed as a whole, from a representative point with a cube shadow map or, with
// area_shadow_rays, by rays to points on its triangles.
struct GpuAreaLight {
  vec4 position;  // xyz representative point; w: first shadow layer (none with area_shadow_rays)
  // x: first GpuAreaTriangle, y: the triangle count; z: the first vertex of a stage of an
  // emitter's particles in the scene's vertex array, w: its particle count. Such a stage
  // (w > 0) is lit particle by particle, and its particles and triangles (eight a particle,
  // for the passes that sample emitters by triangle) are read from the octahedra where the
  // GPU simulation wrote them (passes/area_light_parts.glsl), none listed.
  uvec4 range;
  vec4 particle;  // a particle of the stage: rgb its emitted radiance, w its circumradius
  // x: how far from `position` shadow rays towards it stop (AreaLight::extent); y: 1 when the
  // emitter is double-sided (as GpuAreaTriangle::a.w); z: 1 when a stage of particles is lit
  // by its triangles rather than particle by particle (area_light_parts.glsl, lit_particles);
  // w: for a stage of particles in the scene's light tree (SceneGpu::particle_light_tree),
  // its slot there plus 1, else 0.
  vec4 extent;
  // The declared shape for glossy reflections (scenes::AreaLight::shape_*): xyz centre, w the
  // shape (GIQ_AREA_*); u and v: xyz half vectors (rectangle: sides; tube: half segment; disc:
  // v its unit normal), u.w the radius; v.w: sqrt(area / pi), the radius of the disc of the
  // emitter's area.
  vec4 shape;
  vec4 shape_u;
  vec4 shape_v;
};

#define GIQ_AREA_MESH 0
#define GIQ_AREA_SPHERE 1
#define GIQ_AREA_DISC 2
#define GIQ_AREA_RECTANGLE 3
#define GIQ_AREA_TUBE 4

struct GpuAreaTriangle {
  vec4 a;         // xyz vertex; w: 1 when the emitter is double-sided
  vec4 b;
  vec4 c;
  vec4 radiance;  // rgb emitted radiance
};

// A glowing particle: an octahedron (shaders/octahedron_irradiance.glsl), as
// passes/area_light_parts.glsl reads it.
struct GpuParticleLight {
  vec4 centre;    // xyz centre; w circumradius
  vec4 radiance;  // rgb emitted radiance
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
