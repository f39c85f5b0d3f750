// The rays a rasteriser's texels stand for, for the passes that can be built by casting them
// instead (giq/realtime/pass_builder.h: the reflective shadow maps, the shadow maps). Needs
// scene.glsl.
#ifndef GIQ_TEXEL_RAY_GLSL
#define GIQ_TEXEL_RAY_GLSL

// The ray through a texel centre (in texels from the layer's corner) of a layer `size` texels
// wide whose view-projection has the inverse `clip_to_world`: from the near plane (origin o)
// to the far plane (tmax), the rasteriser's clipping. NDC y runs down the image, as the
// rasteriser's viewport.
void texel_ray(mat4 clip_to_world, vec2 centre, float size, out vec3 o, out vec3 d, out float tmax) {
  vec2 ndc = centre * (2.0 / size) - 1.0;
  vec4 near_h = clip_to_world * vec4(ndc, 0.0, 1.0), far_h = clip_to_world * vec4(ndc, 1.0, 1.0);
  o = near_h.xyz / near_h.w;
  d = far_h.xyz / far_h.w - o;
  tmax = length(d);
  d /= tmax;
}

// Where the ray (o, d) meets the plane of triangle `tri` (as the G-buffer takes its points:
// passes/gbuffer.h); `fallback` for a plane seen exactly edge-on.
vec3 texel_plane_point(vec3 o, vec3 d, uint tri, vec3 fallback) {
  vec3 a, b, c;
  triangle_vertices(tri, a, b, c);
  vec3 ng = normalize(cross(b - a, c - a));
  float denom = dot(d, ng);
  return abs(denom) > 1e-12 ? o + (dot(a - o, ng) / denom) * d : fallback;
}

#endif
