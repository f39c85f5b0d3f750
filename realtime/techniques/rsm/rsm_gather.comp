#version 460
// `rsm`'s gather (Afanasev 2021, section 2.1 and appendix "ReflectiveShadowMappingPS.hlsl";
// Dachsbacher and Stamminger 2005): one bounce of diffuse light from the virtual point lights
// of every reflective shadow map (passes/rsm.h), N samples per pixel at the thesis's polar
// pattern p' = p + r_max xi1 (sin 2 pi xi2, cos 2 pi xi2), the same N (xi1, xi2) pairs for
// every pixel (the thesis's constant buffer `xi`).
//
// Each sample's VPL contributes with the thesis's irradiance formula, written with the
// unnormalised offset v = x - x_p as there:
//   E_p = flux max(0, n_p.v) max(0, n.(-v)) / dot(v, v)^2          (Afanasev 2021, eq. in 2.2)
// with two changes a reviewer should know of:
//   - units: a VPL of flux F emits intensity F/pi cos (a Lambertian patch), so E_p gets 1/pi,
//     and the stored flux is a density (per steradian or per m^2, rsm.frag), so each sample is
//     weighted by 1/pdf of the polar pattern: 2 pi r_max^2 xi1 / N in the ortho window's area,
//     2 pi theta_max sin(theta_max xi1) / N in solid angle for a cube. This is the Monte Carlo
//     estimate of the sum over all texels within r_max; the thesis's weight xi1^2 (from the
//     original paper) is not an unbiased weight for this pattern and leaves the units open.
//   - near field: dot(v,v)^2 becomes dot(v,v) (dot(v,v) + a/pi), a the area one sample stands
//     for, the on-axis irradiance of a disc of that area instead of a point; this bounds a
//     sample landing next to the receiver (the "white glow" in corners) and vanishes with
//     distance, where the thesis's form holds.
// Cube maps are sampled by direction: the cone of half-angle theta_max = pi r_max around the
// direction from the light to the receiver, polar in (angle, azimuth), the face picked per
// sample by the major axis, so samples cross cube edges without seams.
// Output: diffuse albedo / pi x irradiance (the indirect radiance of a Lambertian surface).
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/surface.glsl"
#include "passes/rsm_albedo.glsl"
#include "passes/rsm_shared.h"
#include "passes/rsm.glsl"
#include "techniques/rsm/rsm_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

#include "passes/receiver.glsl"
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 0, rgba32ui) uniform readonly uimage2DArray rsm_surface;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 1, rgba16f) uniform readonly image2DArray rsm_flux;
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 2) readonly buffer Layers { GpuRsmLayer rsm_layers[]; };
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 3) readonly buffer Emitters { GpuRsmEmitter emitters[]; };
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 4) readonly buffer Samples { vec4 xi[]; };
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 5, rgba32f) uniform writeonly image2D out_indirect;

layout(push_constant) uniform Push { RsmGatherPush pc; };

// The VPL at texel t of layer l, seen from (x, n): max(0, n_p.v) max(0, n.-v) / (|v|^2 (|v|^2 + eps))
// times its stored flux density.
vec3 vpl(uint l, ivec2 t, vec3 x, vec3 n, float eps) {
  vec3 f = imageLoad(rsm_flux, ivec3(t, int(l))).rgb;
  if (all(equal(f, vec3(0.0)))) return vec3(0.0);
  uvec4 s = imageLoad(rsm_surface, ivec3(t, int(l)));
  vec3 xp = uintBitsToFloat(s.xyz), np = rsm_decode_normal(s.w);
  vec3 v = x - xp;
  float d2 = dot(v, v);
  float g = max(0.0, dot(np, v)) * max(0.0, dot(n, -v)) / (d2 * (d2 + eps));
  return f * g;
}

// Irradiance at (x, n) from an orthographic layer (a directional light's window).
vec3 gather_ortho(uint l, vec3 x, vec3 n) {
  GpuRsmLayer L = rsm_layers[l];
  float size = L.params.y;
  vec2 uv0 = (L.view_proj * vec4(x, 1.0)).xy * 0.5 + 0.5;
  float r = pc.r_max, width = L.axes.w;
  float n_samples = float(pc.samples);
  float rw2 = (r * width) * (r * width);
  float eps = rw2 / n_samples;  // (pi (r width)^2 / N) / pi
  vec3 sum = vec3(0.0);
  for (uint i = 0u; i < uint(n_samples); ++i) {
    vec4 s = xi[i];
    vec2 uv = uv0 + r * s.x * s.yz;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) continue;
    sum += s.x * vpl(l, ivec2(uv * size), x, n, eps);
  }
  // 1/pdf = 2 pi (r width)^2 xi1 per sample, 1/N, 1/pi of the Lambertian VPL, 1/scale.
  return sum * (2.0 * rw2 / n_samples) * L.params.z;
}

// Irradiance at (x, n) from the six cube layers first..first+5 around c.
vec3 gather_cube(uint first, vec3 c, vec3 x, vec3 n) {
  vec3 d0 = x - c;
  float dl = length(d0);
  if (!(dl > 0.0)) return vec3(0.0);
  vec3 w0 = d0 / dl;
  vec3 t = normalize(abs(w0.x) < 0.9 ? cross(w0, vec3(1.0, 0.0, 0.0)) : cross(w0, vec3(0.0, 1.0, 0.0)));
  vec3 b = cross(w0, t);
  float theta_max = PI * pc.r_max;
  float n_samples = float(pc.samples);
  float size = rsm_layers[first].params.y;
  // The area one sample stands for at the receiver's distance: the cone's solid angle / N.
  float eps = dl * dl * 2.0 * (1.0 - cos(theta_max)) / n_samples;
  vec3 sum = vec3(0.0);
  for (uint i = 0u; i < uint(n_samples); ++i) {
    vec4 s = xi[i];
    // s.w = cos(theta_max xi1); the angle lies in [0, pi], so its sine is the positive root.
    float sa = sqrt(max(0.0, 1.0 - s.w * s.w));
    vec3 w = s.w * w0 + sa * (s.y * t + s.z * b);
    vec3 aw = abs(w);
    uint face = aw.x >= aw.y && aw.x >= aw.z ? (w.x >= 0.0 ? 0u : 1u)
              : aw.y >= aw.z                 ? (w.y >= 0.0 ? 2u : 3u)
                                             : (w.z >= 0.0 ? 4u : 5u);
    vec4 clip = rsm_layers[first + face].view_proj * vec4(c + w, 1.0);
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    ivec2 texel = clamp(ivec2(uv * size), ivec2(0), ivec2(int(size) - 1));
    sum += sa * vpl(first + face, texel, x, n, eps);
  }
  // 1/pdf = 2 pi theta_max sin(a) per sample (solid angle), 1/N, 1/pi, 1/scale.
  return sum * (2.0 * theta_max / n_samples) * rsm_layers[first].params.z;
}

void main() {
  ivec2 lo = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(lo), pc.low_size))) return;
  Receiver r = load_receiver(full_resolution_pixel(lo, int(pc.factor), ivec2(pc.size)));
  vec3 radiance = vec3(0.0);
  if (r.lit) {
    vec3 e = vec3(0.0);
    for (uint i = 0u; i < pc.emitter_count; ++i) {
      GpuRsmEmitter em = emitters[i];
      e += em.layers.y == 1u ? gather_ortho(em.layers.x, r.x, r.n) : gather_cube(em.layers.x, em.position.xyz, r.x, r.n);
    }
    radiance = diffuse_albedo(receiver_surface(r)) / PI * e;
  }
  imageStore(out_indirect, lo, vec4(radiance, 1.0));
}
