#version 460
// Reflective shadow map texel (Afanasev 2021, section 2.1 and 2.2: "flux is the light's colour
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
#include "shaders/surface.glsl"
#include "shaders/lights.glsl"
#include "passes/rsm_shared.h"
#include "passes/rsm.glsl"
#include "passes/rsm_albedo.glsl"

layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 0) readonly buffer Emitters { GpuRsmEmitter emitters[]; };

layout(push_constant) uniform Push { RsmDrawPush pc; };

layout(location = 0) in vec3 in_position;

layout(location = 0) out uvec4 out_surface;
layout(location = 1) out vec4 out_flux;

void main() {
  uint tri = uint(gl_PrimitiveID);
  vec3 a, b, c;
  triangle_vertices(tri, a, b, c);
  vec3 ng = normalize(cross(b - a, c - a));
  vec3 p = in_position;
  GpuRsmEmitter e = emitters[pc.emitter];
  if (e.position.w == GIQ_RSM_AREA && tri - e.layers.z < e.layers.w) discard;
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
  vec2 bary = plane_barycentrics(p, a, b, c);
#ifdef GIQ_ALPHA_MASK
  if (alpha_cut(tri, bary.x, bary.y, alpha_pixel_number(gl_FragCoord.xy, tri))) discard;  // cut-out texels stop no light
#endif
  HitNormals h = hit_normals(tri, bary.x, bary.y, -wi);
  vec3 ns = h.ns;
  // Light below the geometric or the shading horizon is not reflected (direct_light.comp).
  if (h.black || dot(h.ng, wi) <= 0.0 || dot(ns, wi) <= 0.0) density = vec3(0.0);
  Surface s = hit_material(tri, bary.x, bary.y, ns);
  out_surface = rsm_encode_surface(p, ns);
  out_flux = vec4(diffuse_albedo(s) * density * pc.flux_scale, 0.0);
}
