#version 460
// The G-buffer by ray casting instead of rasterisation: one camera ray per pixel centre
// through the BVH. It writes exactly what gbuffer.frag writes (that shader already stores the
// pixel-centre ray's hit), for GPUs whose rasteriser is the bottleneck: on an H100 only a few
// of the SMs run graphics work, while compute runs on all of them.
#extension GL_GOOGLE_include_directive : require

#include "shaders/bvh.glsl"
#include "shaders/camera.glsl"
#include "shaders/surface.glsl"
#include "passes/gbuffer_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = GIQ_SCENE_BINDING_COUNT + 0, rgba32f) uniform writeonly image2D out_position;
layout(binding = GIQ_SCENE_BINDING_COUNT + 1, rgba32f) uniform writeonly image2D out_normal;
layout(binding = GIQ_SCENE_BINDING_COUNT + 2, rgba32ui) uniform writeonly uimage2D out_ids;

layout(push_constant) uniform Push { GBufferPush pc; };

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= int(pc.size.x) || px.y >= int(pc.size.y)) return;
  vec3 o = camera_ray_origin(pc.camera, vec2(px) + 0.5, pc.size);
  vec3 d = camera_ray_direction(pc.camera, vec2(px) + 0.5, pc.size);
  // The rasteriser clips at the near plane along the view axis; so does this.
  float tmin = pc.znear / max(dot(d, pc.camera.forward.xyz), 1e-6);
  RayHit hit = trace_ray(o + tmin * d, d, 1e30, false, true);
  if (hit.triangle == 0xffffffffu) {
    imageStore(out_position, px, vec4(0.0));
    imageStore(out_normal, px, vec4(0.0));
    imageStore(out_ids, px, uvec4(0u));
    return;
  }
  GpuTriangle t = scene_triangles[hit.triangle];
  vec3 a, b, c;
  triangle_vertices(hit.triangle, a, b, c);
  vec3 ng = normalize(cross(b - a, c - a));
  // The hit on the triangle's plane from the camera itself, as gbuffer.frag computes it.
  float denom = dot(d, ng);
  vec3 p = abs(denom) > 1e-12 ? o + (dot(a - o, ng) / denom) * d : o + (tmin + hit.t) * d;
  bool back = denom > 0.0;
  float footprint = pixel_footprint(pc.camera, vec2(px) + 0.5, pc.size, p, ng);
  HitNormals hn = hit_normals(hit.triangle, hit.u, hit.v, d, footprint);
  imageStore(out_position, px, vec4(p, 1.0));
  imageStore(out_normal, px, vec4(hn.ns, footprint));
  imageStore(out_ids, px, uvec4(hit.triangle + 1u, t.v.w, t.extra.y, back ? 1u : 0u));
}
