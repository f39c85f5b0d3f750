#version 460
// Alpha-masked casters (scenes with GIQ_ALPHA_MASK only; the others render depth without a
// fragment shader): cut-out texels cast no shadow, as they stop no ray in the reference, and
// BLEND surfaces cast a dithered one (a fraction alpha of the texels).
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/textures.glsl"

layout(location = 0) in vec4 in_uv;
layout(location = 1) in float in_alpha;

void main() {
  // One draw covers every triangle in SceneGpu order, so gl_PrimitiveID is the global index.
  uint tri = uint(gl_PrimitiveID);
  GpuMaterial m = scene_materials[scene_triangles[tri].v.w];
  vec2 uv = (uint(m.textures2.z) & GIQ_SLOT_BASE_COLOR) != 0u ? in_uv.zw : in_uv.xy;
  if (alpha_pixel_number(gl_FragCoord.xy, tri) >= alpha_coverage(m, tri, uv, in_alpha)) discard;
}
