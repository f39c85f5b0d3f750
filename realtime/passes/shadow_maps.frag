#version 460
// Alpha-masked casters (scenes with GIQ_ALPHA_MASK only; the others render depth without a
// fragment shader): cut-out texels cast no shadow, as they stop no ray in the reference, and
// BLEND surfaces cast a dithered one (a fraction alpha of the texels).
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/textures.glsl"

layout(location = 0) in vec2 in_uv;
layout(location = 1) in float in_alpha;

void main() {
  // One draw covers every triangle in SceneGpu order, so gl_PrimitiveID is the global index.
  uint tri = uint(gl_PrimitiveID);
  if (alpha_pixel_number(gl_FragCoord.xy, tri) >= alpha_coverage(scene_materials[scene_triangles[tri].v.w], tri, in_uv, in_alpha)) discard;
}
