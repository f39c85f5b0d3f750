// The scene as the GPU sees it: one layout shared by the C++ that fills the buffers and the
// GLSL that reads them (std430; every struct is a multiple of 16 bytes with vec3 + scalar
// pairs, which std430 and C++ lay out identically).
#ifndef GIQ_SCENE_SHARED_H
#define GIQ_SCENE_SHARED_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace giq::realtime::gpu {
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using uint = uint32_t;
#endif

// Bindings 0..6 of every pipeline that reads the scene (SceneGpu::descriptors()).
#define GIQ_BINDING_VERTICES 0
#define GIQ_BINDING_TRIANGLES 1
#define GIQ_BINDING_MATERIALS 2
#define GIQ_BINDING_BVH_NODES 3
#define GIQ_BINDING_BVH_PRIMS 4
#define GIQ_BINDING_LIGHTS 5
#define GIQ_BINDING_EMISSIVE 6
#define GIQ_SCENE_BINDING_COUNT 7

#define GIQ_LIGHT_DIRECTIONAL 0
#define GIQ_LIGHT_POINT 1
#define GIQ_LIGHT_SPOT 2

struct GpuVertex {
  vec4 position;  // xyz in the scene's local frame
  vec4 normal;    // xyz unit shading normal
};

struct GpuTriangle {
  uvec4 v;      // x, y, z: global vertex indices; w: material index
  uvec4 extra;  // x: emissive triangle index + 1 (0 = not emissive); y: object id
};

struct GpuMaterial {
  vec4 base_color;      // linear RGB, a unused
  vec4 emissive;        // radiance RGB; w: 1 when emissive
  vec4 specular_color;  // rgb: KHR_materials_specular colour
  vec4 params;          // x metallic, y roughness, z specular factor, w 1 = double-sided
};

// Flattened BVH node (32 bytes). count == 0: interior, `index` = right child (the left child
// follows the node); count > 0: leaf of `count` triangles at prims[index ..].
struct GpuBvhNode {
  vec3 lo;
  uint index;
  vec3 hi;
  uint count;
};

struct GpuLight {
  vec4 position;   // xyz local frame; w: type (GIQ_LIGHT_*)
  vec4 direction;  // xyz unit, the way the light travels; w: range (0 = infinite)
  vec4 radiant;    // rgb: colour x intensity (W/sr for point/spot, W/m^2 for directional)
  vec4 cone;       // x: spot scale, y: spot offset (KHR_lights_punctual); z: first shadow layer
};

struct GpuEmissive {
  uvec4 triangle;  // x: global triangle index
  vec4 radiance;   // rgb: emitted radiance; w: area
  vec4 sampling;   // x: CDF up to and including this triangle; y: probability of choosing it
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
