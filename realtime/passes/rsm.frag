#version 460
// Reflective shadow map texel, rasterised (passes/rsm_texel.glsl says what a texel holds).
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/surface.glsl"
#include "shaders/lights.glsl"
#include "passes/rsm_shared.h"
#include "passes/rsm.glsl"
#include "passes/rsm_albedo.glsl"
#include "passes/rsm_texel.glsl"
#include "shaders/texel_ray.glsl"

layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 0) readonly buffer Emitters { GpuRsmEmitter emitters[]; };
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 1) readonly buffer Layers { GpuRsmLayer layers[]; };

layout(push_constant) uniform Push { RsmLayerPush pc; };

layout(location = 0) in vec3 in_position;

layout(location = 0) out uvec4 out_surface;
layout(location = 1) out vec4 out_flux;

void main() {
  uint tri = uint(gl_PrimitiveID);
  GpuRsmEmitter e = emitters[pc.emitter];
  // An area light's own triangles are left out of its maps (GpuRsmEmitter.layers; punctual
  // lights have an empty range).
  if (tri - e.layers.z < e.layers.w) discard;
  vec3 o, d;
  float tmax;
  texel_ray(layers[pc.layer].clip_to_world, gl_FragCoord.xy, float(pc.size), o, d, tmax);
  vec3 p = texel_plane_point(o, d, tri, in_position);
#ifdef GIQ_ALPHA_MASK
  vec3 a, b, c;
  triangle_vertices(tri, a, b, c);
  vec2 bary = plane_barycentrics(p, a, b, c);
  if (alpha_cut(tri, bary.x, bary.y, alpha_pixel_number(gl_FragCoord.xy, tri))) discard;  // cut-out texels stop no light
#endif
  RsmTexel t = rsm_texel(e, tri, p, pc.flux_scale);
  out_surface = t.surface;
  out_flux = t.flux;
}
