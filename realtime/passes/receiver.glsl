// The receiver of a deferred lighting pass (passes/deferred_gi.h): the G-buffer texel it
// shades. The G-buffer is bound right after the scene, so a pass's own bindings start at
// GIQ_RECEIVER_BINDING_COUNT (the C++ side: GBufferPass::receiver_descriptors()). Needs
// shaders/scene.glsl and shaders/surface.glsl.
#ifndef GIQ_RECEIVER_GLSL
#define GIQ_RECEIVER_GLSL

layout(binding = GIQ_SCENE_BINDING_COUNT + 0, rgba32f) uniform readonly image2D gb_position;
layout(binding = GIQ_SCENE_BINDING_COUNT + 1, rgba32f) uniform readonly image2D gb_normal;
layout(binding = GIQ_SCENE_BINDING_COUNT + 2, rgba32ui) uniform readonly uimage2D gb_ids;
#define GIQ_RECEIVER_BINDING_COUNT (GIQ_SCENE_BINDING_COUNT + 3)

#include "passes/low_resolution.glsl"

struct Receiver {
  bool hit;    // a surface was hit (else the camera sees the environment)
  bool lit;    // it can receive light: a front face, or either face of a double-sided material
  bool back;   // the back face was hit
  uint tri;    // triangle index
  uint material;
  vec3 x;      // local-frame position
  vec3 n;      // shading normal, on the viewer's side (passes/gbuffer.h)
  vec2 bary;   // barycentrics on the triangle's plane (deferred texturing); 0 without textures
  float footprint;  // the pixel's footprint on the surface, for mip selection (texture_lod)
};

Receiver load_receiver(ivec2 px) {
  Receiver r;
  uvec4 ids = imageLoad(gb_ids, px);
  r.hit = ids.x != 0u;
  r.back = ids.w != 0u;
  r.tri = ids.x - 1u;
  r.material = ids.y;
  r.lit = r.hit && (!r.back || scene_materials[ids.y].params.w != 0.0);
  r.x = vec3(0.0);
  r.n = vec3(0.0);
  r.bary = vec2(0.0);
  r.footprint = 0.0;
  if (!r.lit) return r;
  r.x = imageLoad(gb_position, px).xyz;
  vec4 n = imageLoad(gb_normal, px);
  r.n = n.xyz;
  r.footprint = n.w;
#ifdef GIQ_SURFACE_TEXTURES
  vec3 ta, tb, tc;
  triangle_vertices(r.tri, ta, tb, tc);
  r.bary = plane_barycentrics(r.x, ta, tb, tc);
#endif
  return r;
}

// The receiver's geometric normal, on the viewer's side.
vec3 receiver_geometric_normal(Receiver r) {
  vec3 a, b, c;
  triangle_vertices(r.tri, a, b, c);
  return normalize(cross(b - a, c - a)) * (r.back ? -1.0 : 1.0);
}

// The origin of a ray that leaves the receiver (shaders/sampling.glsl's offset_ray), lifted
// further along ng by 2^-16 of the larger of the point's and the camera's (`eye`) coordinates:
// the G-buffer point is where the camera ray meets the triangle's plane, so its error along
// the normal grows with both, and a plane through the origin seen from far away would
// otherwise have its rays start below it.
vec3 receiver_ray_origin(Receiver r, vec3 ng, vec3 eye) {
  vec3 m = max(abs(r.x), abs(eye));
  return offset_ray(r.x, ng) + ng * (max(m.x, max(m.y, m.z)) * (1.0 / 65536.0));
}

// The receiver's material at its G-buffer point, textures looked up again there at the
// pixel's mip levels.
Surface receiver_surface(Receiver r) { return hit_material(r.tri, r.bary.x, r.bary.y, r.n, r.footprint); }

#endif
