#version 460
// A shadow-map layer by ray casting instead of rasterisation (passes/shadow_maps.h): one ray
// per texel centre through the BVH, from the layer's near plane to its far plane, as the
// rasteriser clips (shaders/texel_ray.glsl). A texel stores the depth the rasteriser would: the
// closest surface's point on its triangle's plane, projected, plus the slope-scaled bias
// (Vulkan's depth bias, m = the larger of the depth's changes to the next texel in x and in
// y, measured on the same plane); 1 where nothing is seen. Written to a buffer that the pass
// copies into the depth layer. For GPUs whose graphics units are the bottleneck
// (giq/realtime/pass_builder.h).
#extension GL_GOOGLE_include_directive : require

#include "shaders/bvh.glsl"
#include "shaders/texel_ray.glsl"
#include "passes/shadow_maps_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 0) readonly buffer Layers { GpuShadowLayer shadow_layers[]; };
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 1) writeonly buffer Depth { float depth[]; };

layout(push_constant) uniform Push { ShadowRayPush pc; };

// The depth of the point where the ray (o, d) meets the plane of `tri`.
float plane_depth(GpuShadowLayer l, vec3 o, vec3 d, uint tri, vec3 fallback) {
  vec4 c = l.view_proj * vec4(texel_plane_point(o, d, tri, fallback), 1.0);
  return c.z / c.w;
}

// The same for the ray through texel centre `centre`.
float plane_depth(GpuShadowLayer l, vec2 centre, uint tri, vec3 fallback) {
  vec3 o, d;
  float tmax;
  texel_ray(l.clip_to_world, centre, float(pc.size), o, d, tmax);
  return plane_depth(l, o, d, tri, fallback);
}

void main() {
  uvec2 px = gl_GlobalInvocationID.xy;
  if (px.x >= pc.size || px.y >= pc.size) return;
  GpuShadowLayer l = shadow_layers[pc.layer];
  vec2 centre = vec2(px) + 0.5;
  vec3 o, d;
  float tmax;
  texel_ray(l.clip_to_world, centre, float(pc.size), o, d, tmax);
  RayHit hit = trace_ray(o, d, tmax, false, false, pc.skip.zw);
  float z = 1.0;
  if (hit.triangle != 0xffffffffu) {
    vec3 p = o + hit.t * d;
    z = plane_depth(l, o, d, hit.triangle, p);
    float m = max(abs(plane_depth(l, centre + vec2(1.0, 0.0), hit.triangle, p) - z),
                  abs(plane_depth(l, centre + vec2(0.0, 1.0), hit.triangle, p) - z));
    z = clamp(z + pc.slope_bias * m, 0.0, 1.0);
  }
  depth[px.y * pc.size + px.x] = z;
}
