#version 460
// Reflective shadow map texel (seed 000, section 2.1 and 2.2: "flux is the light's colour
// times the surface colour"): the surface the light sees through this texel as a virtual
// point light (position, normal) and the light it reflects diffusely.
//
// Flux is stored as a density, so that it does not depend on the texel's size and a lookup
// can integrate it over the light's view: per steradian seen from the light for a cube face
// (diffuse albedo x the light's radiant intensity towards the texel: W/sr), per square metre
// of the light's image plane for an orthographic layer (diffuse albedo x the sun's irradiance:
// W/m^2). The flux a texel stands for is the density times its solid angle or area. Values are
// multiplied by the layer's flux scale (1 / the light's brightest channel) so that fp16 keeps
// its relative precision for any light and never overflows.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/brdf.glsl"
#include "shaders/lights.glsl"
#include "passes/rsm_shared.h"
#include "passes/rsm.glsl"

layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 0) readonly buffer Emitters { GpuRsmEmitter emitters[]; };

layout(push_constant) uniform Push { RsmDrawPush pc; };

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;

layout(location = 0) out uvec4 out_surface;
layout(location = 1) out vec4 out_flux;

// The part of incident light a surface re-emits diffusely: the diffuse lobe's albedo of
// brdf.glsl, with the dielectric Fresnel term taken at normal incidence (the hemispherical
// average is not needed to first order for the VPL's flux).
vec3 diffuse_albedo(GpuMaterial m) {
  Surface s = make_surface(m, vec3(0.0, 0.0, 1.0));
#ifdef GIQ_SPECULAR
  vec3 f0 = dielectric_f0(s);
  return (1.0 - s.metallic) * (1.0 - max(f0.r, max(f0.g, f0.b))) * s.base_color;
#else
  return (1.0 - s.metallic) * s.base_color;
#endif
}

void main() {
  uint tri = uint(gl_PrimitiveID);
  GpuTriangle t = scene_triangles[tri];
  vec3 a, b, c;
  triangle_vertices(tri, a, b, c);
  vec3 ng = normalize(cross(b - a, c - a));
  vec3 p = in_position;
  GpuRsmEmitter e = emitters[uint(pc.params.x)];
  vec3 wi;       // towards the light
  vec3 density;  // intensity towards p (W/sr) or irradiance (W/m^2, directional)
  if (e.position.w == GIQ_RSM_AREA) {
    vec3 d = p - e.position.xyz;
    float dist = length(d);
    wi = dist > 0.0 ? -d / dist : ng;
    float ce = dot(e.normal.xyz, -wi);
    density = e.intensity.rgb * (e.normal.w != 0.0 ? abs(ce) : max(ce, 0.0));
  } else {
    GpuLight l = scene_lights[uint(e.intensity.w)];
    float dist;
    density = punctual_incident(l, p, wi, dist);
    if (int(l.position.w) != GIQ_LIGHT_DIRECTIONAL) density *= dist * dist;
  }
  bool back = dot(ng, wi) < 0.0;
  GpuMaterial mat = scene_materials[t.v.w];
  // The light sees the back of a one-sided material: black, as in the direct-lighting pass.
  if (back && mat.params.w == 0.0) density = vec3(0.0);
  vec3 ngv = back ? -ng : ng;
  vec3 ns = dot(in_normal, in_normal) > 0.0 ? normalize(in_normal) : ngv;
  if (dot(ns, ngv) < 0.0) ns = -ns;
  // Light arriving below the shading horizon is not reflected (direct_light.comp's cos_i > 0).
  if (dot(ns, wi) <= 0.0) density = vec3(0.0);
  out_surface = rsm_encode_surface(p, ns);
  out_flux = vec4(diffuse_albedo(mat) * density * pc.params.y, 0.0);
}
