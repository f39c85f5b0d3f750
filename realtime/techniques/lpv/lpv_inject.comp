#version 460
// LPV injection (Afanasev 2021, section 3.2 and appendix "RSMDownsamplerPS.hlsl", "LPVInjection.hlsl"):
// each k x k block of a reflective-shadow-map layer (passes/rsm.h) becomes one VPL by the
// thesis's brightest-texel scheme: the block's brightest texel (luminance of its flux plus
// max(0, n.-light direction)) picks a cell, and the texels whose cells lie within a squared
// distance of 10 cells of it are merged: mean position, normalised mean normal, and the SUM of
// their flux (the thesis divides the sum by the texel count, which drops the flux of all but one
// texel; the sum keeps the power the texels stand for). Empty texels (no surface, zero flux) are
// skipped; the thesis merges them as points at the origin.
// The VPL is injected into the cell holding its position moved half a cell along its normal
// (the thesis's offset), as the 2-band SH of its radiant intensity flux/pi max(0, n.w).
// Cells accumulate in fixed point with integer atomics: exact, order-independent sums (the
// result is deterministic) without the float-atomics extension.
#extension GL_GOOGLE_include_directive : require

#include "passes/rsm_shared.h"
#include "passes/rsm.glsl"
#include "techniques/lpv/lpv_shared.h"
#include "techniques/lpv/lpv_sh.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0, rgba32ui) uniform readonly uimage2DArray rsm_surface;
layout(binding = 1, rgba16f) uniform readonly image2DArray rsm_flux;
layout(std430, binding = 2) readonly buffer Layers { GpuRsmLayer rsm_layers[]; };
layout(std430, binding = 3) readonly buffer Emitters { GpuRsmEmitter emitters[]; };
layout(std430, binding = 4) buffer Inject { int inject[]; };

layout(push_constant) uniform Push { LpvGrid grid; };

#define K_MAX 8

float luminance(vec3 c) { return dot(c, vec3(0.299, 0.587, 0.114)); }

void main() {
  uint l = gl_GlobalInvocationID.z;
  if (l >= grid.rsm_layers) return;
  GpuRsmLayer L = rsm_layers[l];
  int size = int(L.params.y), k = int(grid.rsm_downsample);
  ivec2 block = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(block * k, ivec2(size)))) return;
  GpuRsmEmitter e = emitters[uint(L.params.w)];
  bool ortho = L.params.x == GIQ_RSM_ORTHO;
  vec3 origin = grid.origin.xyz;
  float cell = grid.origin.w;
  int res = int(grid.resolution);

  // The brightest texel's cell.
  float best = -1.0;
  ivec3 best_cell = ivec3(0);
  for (int y = 0; y < k; ++y)
    for (int x = 0; x < k; ++x) {
      ivec2 t = block * k + ivec2(x, y);
      if (any(greaterThanEqual(t, ivec2(size)))) continue;
      vec3 f = imageLoad(rsm_flux, ivec3(t, int(l))).rgb;
      if (all(equal(f, vec3(0.0)))) continue;
      uvec4 s = imageLoad(rsm_surface, ivec3(t, int(l)));
      vec3 p = uintBitsToFloat(s.xyz), n = rsm_decode_normal(s.w);
      vec3 light_dir = ortho ? L.axes.xyz : normalize(p - e.position.xyz);
      float lum = luminance(f) + max(0.0, dot(n, -light_dir));
      if (lum > best) {
        best = lum;
        best_cell = ivec3(floor((p - origin) / cell));
      }
    }
  if (best < 0.0) return;

  // Merge the texels near it. Flux of a texel = stored density / scale x its measure: area
  // (W/size)^2 in an ortho window, solid angle (2/size)^2 / (1 + u^2 + v^2)^(3/2) on a cube face.
  vec3 flux = vec3(0.0), pos = vec3(0.0), nrm = vec3(0.0);
  float count = 0.0;
  for (int y = 0; y < k; ++y)
    for (int x = 0; x < k; ++x) {
      ivec2 t = block * k + ivec2(x, y);
      if (any(greaterThanEqual(t, ivec2(size)))) continue;
      vec3 f = imageLoad(rsm_flux, ivec3(t, int(l))).rgb;
      if (all(equal(f, vec3(0.0)))) continue;
      uvec4 s = imageLoad(rsm_surface, ivec3(t, int(l)));
      vec3 p = uintBitsToFloat(s.xyz);
      ivec3 d = ivec3(floor((p - origin) / cell)) - best_cell;
      if (dot(vec3(d), vec3(d)) >= 10.0) continue;
      float measure;
      if (ortho) {
        float texel = L.axes.w / float(size);
        measure = texel * texel;
      } else {
        vec2 uv = (vec2(t) + 0.5) / float(size) * 2.0 - 1.0;
        float r2 = 1.0 + dot(uv, uv);
        measure = (4.0 / float(size * size)) / (r2 * sqrt(r2));
      }
      flux += f * (L.params.z * measure);
      pos += p;
      nrm += rsm_decode_normal(s.w);
      count += 1.0;
    }
  if (count == 0.0 || dot(nrm, nrm) == 0.0) return;
  pos /= count;
  nrm = normalize(nrm);
  ivec3 c = ivec3(floor((pos - origin) / cell + 0.5 * nrm));
  if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(c, ivec3(res)))) return;
  vec4 sh = cos_lobe_sh(nrm) / PI_LPV;
  int base = 12 * lpv_cell_index(c, res);
  float q = grid.injection_scale;
  for (int ch = 0; ch < 3; ++ch) {
    vec4 v = sh * flux[ch] * q;
    for (int i = 0; i < 4; ++i) {
      int iv = int(round(v[i]));
      if (iv != 0) atomicAdd(inject[base + 4 * ch + i], iv);
    }
  }
}
