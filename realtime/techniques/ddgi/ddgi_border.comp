#version 460
// `ddgi`'s tile borders (Majercik et al. 2019): every border texel of every tile
// repeats the interior texel across the folded edge (oct_border_source), so that bilinear
// filtering near a tile's edge is seamless on the sphere. Runs after ddgi_blend.comp.
#extension GL_GOOGLE_include_directive : require

#include "shaders/sampling.glsl"
#include "techniques/ddgi/ddgi_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) readonly buffer Volume { GpuDdgiVolume ddgi; };
layout(std430, binding = 1) readonly buffer Probes { GpuDdgiProbe ddgi_probes[]; };
#ifdef GIQ_DDGI_DISTANCE
layout(binding = 2, rg32f) uniform image2D atlas;
#else
layout(binding = 2, rgba32f) uniform image2D atlas;
#endif

#define GIQ_DDGI_NO_SAMPLERS
#include "techniques/ddgi/ddgi_volume.glsl"

void main() {
  const uint n = GIQ_DDGI_TEXELS;
  uvec2 px = gl_GlobalInvocationID.xy;
  uvec2 tile = px / (n + 2u);
  if (tile.x >= ddgi.tiles.x) return;
  uint probe = tile.y * ddgi.tiles.x + tile.x;
  if (probe >= ddgi.counts.w) return;
  uvec2 t = px % (n + 2u);
  if (all(greaterThan(t, uvec2(0u))) && all(lessThan(t, uvec2(n + 1u)))) return;  // interior
  uvec2 s = oct_border_source(t, n);
  imageStore(atlas, ivec2(px), imageLoad(atlas, ivec2(tile * (n + 2u) + s)));
}
