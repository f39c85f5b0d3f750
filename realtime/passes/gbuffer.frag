#version 460
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/camera.glsl"
#include "shaders/surface.glsl"
#include "passes/gbuffer_shared.h"

layout(push_constant) uniform Push { GBufferPush pc; };

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out uvec4 out_ids;

void main() {
  // One draw covers every triangle in SceneGpu order, so gl_PrimitiveID is the global index.
  uint tri = uint(gl_PrimitiveID);
  GpuTriangle t = scene_triangles[tri];
  vec3 a, b, c;
  triangle_vertices(tri, a, b, c);
  vec3 ng = normalize(cross(b - a, c - a));
  vec3 o = camera_ray_origin(pc.camera, gl_FragCoord.xy, pc.size);
  vec3 d = camera_ray_direction(pc.camera, gl_FragCoord.xy, pc.size);
  float denom = dot(d, ng);
  // The ray through the pixel centre meets the triangle's plane at t; a plane seen exactly
  // edge-on falls back to the rasteriser's own depth.
  float tp = abs(denom) > 1e-12 ? dot(a - o, ng) / denom : 0.0;
  vec3 p = o + tp * d;
  // glTF 2.0, 3.9.5: the back of a single-sided surface is culled (what is behind shows).
  if (denom > 0.0 && scene_materials[t.v.w].params.w == 0.0) discard;
  vec2 bary = plane_barycentrics(p, a, b, c);
#ifdef GIQ_ALPHA_MASK
  // Cut-outs are no surface: the triangles behind them show through (glTF 2.0, 3.9.4).
  if (alpha_cut(tri, bary.x, bary.y, alpha_pixel_number(gl_FragCoord.xy, tri))) discard;
#endif
  // The pixel's footprint on the surface: mip selection for its textures (texture_lod).
  float footprint = pixel_footprint(pc.camera, gl_FragCoord.xy, pc.size, p, ng);
  HitNormals hn = hit_normals(tri, bary.x, bary.y, d, footprint);
  out_position = vec4(p, 1.0);
  out_normal = vec4(hn.ns, footprint);
  out_ids = uvec4(tri + 1u, t.v.w, t.extra.y, denom > 0.0 ? 1u : 0u);
}
