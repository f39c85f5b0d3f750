#version 460
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/camera.glsl"
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
  vec3 o = pc.camera.position.xyz;
  vec3 d = camera_ray_direction(pc.camera, gl_FragCoord.xy, pc.viewport.xy);
  float denom = dot(d, ng);
  // The ray through the pixel centre meets the triangle's plane at t; a plane seen exactly
  // edge-on falls back to the rasteriser's own depth.
  float tp = abs(denom) > 1e-12 ? dot(a - o, ng) / denom : 0.0;
  vec3 p = o + tp * d;
  // Barycentrics of p for the shading normal.
  vec3 e1 = b - a, e2 = c - a, ep = p - a;
  float d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2), dp1 = dot(ep, e1), dp2 = dot(ep, e2);
  float den = d11 * d22 - d12 * d12;
  float u = den != 0.0 ? clamp((d22 * dp1 - d12 * dp2) / den, 0.0, 1.0) : 0.0;
  float v = den != 0.0 ? clamp((d11 * dp2 - d12 * dp1) / den, 0.0, 1.0) : 0.0;
  vec3 ns = (1.0 - u - v) * scene_vertices[t.v.x].normal.xyz + u * scene_vertices[t.v.y].normal.xyz +
            v * scene_vertices[t.v.z].normal.xyz;
  bool back = dot(ng, d) > 0.0;
  vec3 ngv = back ? -ng : ng;
  ns = dot(ns, ns) > 0.0 ? normalize(ns) : ngv;
  if (dot(ns, ngv) < 0.0) ns = -ns;
  out_position = vec4(p, 1.0);
  out_normal = vec4(ns, 0.0);
  out_ids = uvec4(tri + 1u, t.v.w, t.extra.y, back ? 1u : 0u);
}
