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
  uint pad0, pad1;
};

// An emissive mesh as one area light: its triangles are integrated exactly (unshadowed), and
// shadowed as a whole from a representative point with a cube shadow map.
struct GpuAreaLight {
  vec4 position;  // xyz representative point; w: first shadow layer
  uvec4 range;    // x: first GpuAreaTriangle, y: count
  vec4 extent;    // x: how far from `position` shadow rays towards it stop (AreaLight::extent)
};

struct GpuAreaTriangle {
  vec4 a;         // xyz vertex; w: 1 when the emitter is double-sided
  vec4 b;
  vec4 c;
  vec4 radiance;  // rgb emitted radiance
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
