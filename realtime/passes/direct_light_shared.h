// Structures shared by passes/direct_light.cpp and direct_light.comp.
#ifndef GIQ_DIRECT_LIGHT_SHARED_H
#define GIQ_DIRECT_LIGHT_SHARED_H

#include "shaders/camera_shared.h"

#ifdef __cplusplus
namespace giq::realtime::gpu {
using uvec4 = glm::uvec4;
#endif

struct DirectPush {
  GpuCamera camera;
  vec4 viewport;     // x width, y height, z normal offset (texels), w PCF radius
  vec4 environment;  // rgb constant environment radiance
  uvec4 counts;      // x punctual lights, y area lights
};

// An emissive mesh as one area light: its triangles are integrated exactly (unshadowed), and
// shadowed as a whole from a representative point with a cube shadow map.
struct GpuAreaLight {
  vec4 position;  // xyz representative point; w: first shadow layer
  uvec4 range;    // x: first GpuAreaTriangle, y: count
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
