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
using ivec4 = glm::ivec4;
using uint = uint32_t;
#endif

// Bindings 0..9 of every pipeline that reads the scene (SceneGpu::descriptors()).
#define GIQ_BINDING_VERTICES 0
#define GIQ_BINDING_TRIANGLES 1
#define GIQ_BINDING_MATERIALS 2
#define GIQ_BINDING_BVH_NODES 3
#define GIQ_BINDING_BVH_PRIMS 4
#define GIQ_BINDING_LIGHTS 5
#define GIQ_BINDING_EMISSIVE 6
// Texture coordinates and tangents, texture descriptors and the texel decode table: filled
// only for scenes whose FeatureSet has textures, normal maps or alpha masks (an empty 16-byte
// buffer otherwise). Texels are read through device addresses (GpuTexture::texels).
#define GIQ_BINDING_VERTEX_EXTRA 7
#define GIQ_BINDING_TEXTURES 8
#define GIQ_BINDING_DECODE 9
#define GIQ_SCENE_BINDING_COUNT 10

#define GIQ_LIGHT_DIRECTIONAL 0
#define GIQ_LIGHT_POINT 1
#define GIQ_LIGHT_SPOT 2

// GpuTriangle::extra.z bits: what the triangle's mesh provides (scenes::Mesh).
#define GIQ_TRIANGLE_HAS_UVS 1u
#define GIQ_TRIANGLE_HAS_TANGENTS 2u
#define GIQ_TRIANGLE_HAS_NORMALS 4u
#define GIQ_TRIANGLE_HAS_COLORS 8u
#define GIQ_TRIANGLE_HAS_UVS2 16u

// Texture slots, as bits of GpuMaterial::textures2.z: the slots whose texture reads the
// material's second texture-coordinate mapping (scenes::TextureSlot, Material::uv2_slots).
#define GIQ_SLOT_BASE_COLOR 1u
#define GIQ_SLOT_METALLIC_ROUGHNESS 2u
#define GIQ_SLOT_NORMAL 4u
#define GIQ_SLOT_EMISSIVE 8u
#define GIQ_SLOT_SPECULAR 16u
#define GIQ_SLOT_SPECULAR_COLOR 32u

// GpuTexture::info.w: wrap_s | wrap_t << 2 | filter << 4 | format << 5 (scenes::Wrap,
// scenes::Filter, scenes::TexelFormat order).
#define GIQ_WRAP_REPEAT 0u
#define GIQ_WRAP_CLAMP 1u
#define GIQ_WRAP_MIRROR 2u
#define GIQ_FILTER_NEAREST 0u
#define GIQ_FILTER_LINEAR 1u
#define GIQ_TEXELS_RGBA8_SRGB 0u
#define GIQ_TEXELS_RGBA8_UNORM 1u
#define GIQ_TEXELS_RGBA32F 2u
// The decode table is scenes::decode_table: entry c (c < 256) is the float c / 255, entry
// 256 + c the sRGB decoding of c / 255.
#define GIQ_DECODE_SRGB 256u

struct GpuVertex {
  vec4 position;  // xyz in the scene's local frame
  vec4 normal;    // xyz unit shading normal
};

// Per vertex, beside GpuVertex, for scenes with textures or vertex colours only.
struct GpuVertexExtra {
  vec4 tangent;  // xyz tangent, w bitangent sign (scenes::Mesh::tangents)
  vec4 uv;       // xy, zw: the material's first and second mapping (scenes::Mesh::uvs, uvs2)
  vec4 color;    // COLOR_0, linear RGBA (scenes::Mesh::colors); white without
};

struct GpuTriangle {
  uvec4 v;      // x, y, z: global vertex indices; w: material index
  uvec4 extra;  // x: emissive triangle index + 1 (0 = not emissive); y: object id;
                // z: GIQ_TRIANGLE_HAS_* bits
};

struct GpuMaterial {
  vec4 base_color;      // linear RGB; a: alpha factor (alpha mask)
  vec4 emissive;        // radiance RGB; w: 1 when emissive
  vec4 specular_color;  // rgb: KHR_materials_specular colour
  vec4 params;          // x metallic, y roughness, z specular factor, w 1 = double-sided
  ivec4 textures;       // texture indices, -1 = none: x base colour, y metallic-roughness,
                        // z emissive, w normal
  ivec4 textures2;      // x specular (A channel), y specular colour (RGB), z the GIQ_SLOT_* reading uv.zw
  vec4 mask;            // x: alpha mode (0 OPAQUE, 1 MASK, 2 BLEND), y: alpha cutoff, z: normal scale
};

// A texture: its words from `first`, row-major, first row = v 0, exactly as scenes::Texture
// holds them: one word a texel (8-bit RGBA, R in the low byte) or four (float RGBA bits); then
// its mip levels, each max(1, size >> level) a side (shaders/texture_mips.comp).
struct GpuTexture {
  uvec4 info;    // x mip levels (1: level 0 only), y width, z height, w wrap, filter and format (GIQ_WRAP_*, GIQ_FILTER_*, GIQ_TEXELS_*)
  uvec4 texels;  // xy the device address of the first texel word (low, high), zw unused
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
