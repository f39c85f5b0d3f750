// Reflective shadow map texel (Afanasev 2021, section 2.1 and 2.2: "flux is the light's colour
// times the surface colour"): the surface the light sees through this texel as a virtual
// point light (position, normal) and the light it reflects diffusely. Written once for both
// builders: rsm.frag (rasterised) and rsm_rays.comp (one ray per texel centre). Both take the
// texel's point where the ray through its centre meets the triangle's plane, as the G-buffer
// does (passes/gbuffer.h), not the rasteriser's interpolated position: that one is off by the
// rasteriser's subpixel snapping (2^-8 texel on lavapipe, 3e-5 m on the test Cornell box's
// 64-texel faces), enough to change a texel's flux under a spot light's falloff by 0.2 %.
//
// Flux is stored as a density, so that it does not depend on the texel's size and a lookup
// can integrate it over the light's view: per steradian seen from the light for a cube face
// (diffuse albedo x the light's radiant intensity towards the texel: W/sr), per square metre
// of the light's image plane for an orthographic layer (diffuse albedo x the sun's irradiance:
// W/m^2). The flux a texel stands for is the density times its solid angle or area. Values are
// multiplied by the layer's flux scale (1 / the light's brightest channel) so that fp16 keeps
// its relative precision for any light and never overflows.
// Needs scene.glsl, surface.glsl, lights.glsl, rsm_shared.h, rsm.glsl, rsm_albedo.glsl; the
// builders take the texel's ray and point from shaders/texel_ray.glsl.
#ifndef GIQ_RSM_TEXEL_GLSL
#define GIQ_RSM_TEXEL_GLSL

struct RsmTexel {
  uvec4 surface;  // rsm_encode_surface
  vec4 flux;      // flux density x flux_scale
};

// Point p of triangle `tri` (texel_plane_point), lit by emitter e. The caller has already left
// out what no texel shows: the emitter's own triangles and alpha cut-outs.
RsmTexel rsm_texel(GpuRsmEmitter e, uint tri, vec3 p, float flux_scale) {
  vec3 a, b, c;
  triangle_vertices(tri, a, b, c);
  vec3 ng = normalize(cross(b - a, c - a));
  vec2 bary = plane_barycentrics(p, a, b, c);
  vec3 wi;       // towards the light
  vec3 density;  // intensity towards p (W/sr) or irradiance (W/m^2, directional)
  if (e.position.w == GIQ_RSM_AREA) {
    vec3 d = p - e.position.xyz;
    float dist = length(d);
    wi = dist > 0.0 ? -d / dist : ng;
    float ce = dot(e.normal.xyz, -wi);
    density = e.intensity.rgb * (e.normal.w == 2.0 ? 0.25 : e.normal.w != 0.0 ? abs(ce) : max(ce, 0.0));
  } else {
    GpuLight l = scene_lights[uint(e.intensity.w)];
    float dist;
    density = punctual_incident(l, p, wi, dist);
    if (int(l.position.w) != GIQ_LIGHT_DIRECTIONAL) density *= dist * dist;
  }
  // The surface as the reference describes it, seen from the light: normals (interpolated,
  // normal-mapped, on the light's side; the back of a one-sided material is black, as in the
  // direct-lighting pass) and the material with its textures at this point.
  HitNormals h = hit_normals(tri, bary.x, bary.y, -wi);
  vec3 ns = h.ns;
  // Light below the geometric or the shading horizon is not reflected (direct_light.comp).
  if (h.black || dot(h.ng, wi) <= 0.0 || dot(ns, wi) <= 0.0) density = vec3(0.0);
  Surface s = hit_material(tri, bary.x, bary.y, ns);
  RsmTexel t;
  t.surface = rsm_encode_surface(p, ns);
  t.flux = vec4(diffuse_albedo(s) * density * flux_scale, 0.0);
  return t;
}

#endif
