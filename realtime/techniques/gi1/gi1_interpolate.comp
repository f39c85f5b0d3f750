#version 460
// `gi1`: every pixel's irradiance from the probes around it (Boissé et al. 2022,
// section 2.4.1). The pixel's position is jittered by up to half a tile, a new offset each
// frame, so that neighbouring pixels do not all read the same probes (the denoiser averages
// the dither away); the jitter is dropped where it lands off the pixel's plane (Wright 2021).
// The probes of the four tiles nearest that position, or the nearest beyond each in its
// direction where a tile has none (the mask's search, gi1_mask.glsl), are weighted
// bilinearly, by how well their normals agree with the pixel's and by the distance of each
// probe from the pixel's plane, zero beyond a cell size (no light from a surface that is not
// this one). When every weight is zero the interpolation is relaxed: the probes found count
// equally, and the pixel is flagged for the denoiser. Each probe gives the irradiance its
// spherical harmonics hold for the pixel's normal in the probe's frame (section 2.4.2).
// Output: irradiance (rgb) and the relaxed flag (w: 1 relaxed, 0 not, -1 no surface); the
// `probes` layer shows where probes sit (R), which carry history (G) and which were traced
// this frame (B).
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/surface.glsl"
#include "shaders/sampling.glsl"
#include "techniques/gi1/gi1_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

#include "passes/receiver.glsl"
#include "techniques/gi1/gi1_common.glsl"
layout(binding = GIQ_GI1_BINDING_COUNT + 0, rgba32f) uniform writeonly image2D out_raw;
layout(binding = GIQ_GI1_BINDING_COUNT + 1, rgba32f) uniform writeonly image2D out_probes;
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 2) readonly buffer Mask { uint probe_mask[]; };
// The near field (gi1_near_field.comp), read where it is on.
layout(binding = GIQ_GI1_BINDING_COUNT + 3, rgba32f) uniform readonly image2D near_field;
layout(binding = GIQ_GI1_BINDING_COUNT + 4, rgba16f) uniform readonly image2D bent_normal;

#include "techniques/gi1/gi1_probe.glsl"
#include "techniques/gi1/gi1_mask.glsl"

vec3 probe_irradiance(uint t, vec3 n, float visible) {
  vec4 sh[GIQ_GI1_SH];
  for (uint k = 0u; k < GIQ_GI1_SH; ++k) sh[k] = harmonics[t * GIQ_GI1_SH + k];
  return gi1_sh_irradiance(sh, to_local(n, probes[t].normal.xyz), visible);
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), gi1.size.xy))) return;
  uvec2 tile = uvec2(px) / GIQ_GI1_PROBE;
  GpuGi1Probe own = probes[gi1_tile_index(tile)];
  bool here = own.info.x == gi1_pack_pixel(uvec2(px));
  imageStore(out_probes, px, vec4(here ? 1.0 : 0.0, here && (own.info.y & GIQ_GI1_REPROJECTED) != 0u ? 1.0 : 0.0,
                                  here && (own.info.y & GIQ_GI1_SPAWNED) != 0u ? 1.0 : 0.0, 1.0));
  Receiver r = load_receiver(px);
  if (!r.lit) {
    imageStore(out_raw, px, vec4(0.0, 0.0, 0.0, -1.0));
    return;
  }
  float depth = gi1_view_depth(gi1.camera, r.x);
  float cell = gi1_screen_cell(gi1, depth);
  // With the near field the probes light only the visible cone about the bent normal, and
  // the near field the rest (section 3.1).
  vec3 near = vec3(0.0), far_normal = r.n;
  float visible = 1.0;
  if ((gi1.counts.w & GIQ_GI1_NEAR_FIELD) != 0u) {
    vec4 nf = imageLoad(near_field, px);
    near = nf.rgb;
    visible = nf.w;
    if (visible < 1.0) far_normal = normalize(imageLoad(bent_normal, px).xyz);
  }
  // The jitter, up to half a tile, dropped where it lands off the pixel's plane.
  Rng rng = rng_init(uvec2(px), gi1.jitter.z, gi1_stream(gi1, 3u));
  vec2 jitter = (vec2(rng_next(rng), rng_next(rng)) - 0.5) * float(GIQ_GI1_PROBE);
  ivec2 moved = clamp(px + ivec2(round(jitter)), ivec2(0), ivec2(gi1.size.xy) - 1);
  if (moved != px) {
    Receiver m = load_receiver(moved);
    if (!m.lit || abs(dot(m.x - r.x, r.n)) > 0.25 * cell) jitter = vec2(0.0);
  }
  // The 2x2 tiles whose centres surround that position, and its bilinear weights among them;
  // where a tile has no probe, the nearest one beyond it in that direction (Algorithm 4).
  vec2 f = (vec2(px) + 0.5 + jitter) / float(GIQ_GI1_PROBE) - 0.5;
  ivec2 base = ivec2(floor(f));
  vec2 w = f - vec2(base);
  vec3 e = vec3(0.0), e_near = vec3(0.0), e_any = vec3(0.0);
  float total = 0.0, n_near = 0.0, n_any = 0.0;
  for (int j = 0; j < 4; ++j) {
    ivec2 o = ivec2(j & 1, j >> 1);
    uint t = gi1_find_probe(base, o);
    if (t == GIQ_GI1_NONE) continue;
    GpuGi1Probe p = probes[t];
    vec3 et = probe_irradiance(t, far_normal, visible);
    float plane = abs(dot(p.position.xyz - r.x, r.n));
    float weight = (o.x == 1 ? w.x : 1.0 - w.x) * (o.y == 1 ? w.y : 1.0 - w.y) *
                   max(dot(p.normal.xyz, r.n), 0.0) * max(1.0 - plane / cell, 0.0);
    e += weight * et;
    total += weight;
    e_any += et;
    n_any += 1.0;
    if (plane < cell) {
      e_near += et;
      n_near += 1.0;
    }
  }
  // Relaxed interpolation where every weight is zero: the probes found count equally, those
  // near the pixel's plane if any.
  bool relaxed = !(total > 0.0);
  e = !relaxed ? e / total : (n_near > 0.0 ? e_near / n_near : (n_any > 0.0 ? e_any / n_any : vec3(0.0)));
  imageStore(out_raw, px, vec4(e + near, relaxed ? 1.0 : 0.0));
}
