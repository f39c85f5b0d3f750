#version 460
// `gi1`: the world cache's tiles that received samples this frame blend them into
// their cells and rebuild their mip levels (Boissé et al. 2022, section 2.2.3). A cell keeps
// the moving average of its samples over the last `samples` of them (the exponential moving
// average of Karis 2014 with weight k / n, n growing to its cap, so that a new cell is the
// plain mean of what it has); the mips average their four children weighted by their sample
// counts, and count all of them, so that a query can take the finest level that has enough.
#extension GL_GOOGLE_include_directive : require

#include "techniques/gi1/gi1_shared.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Frame { GpuGi1Frame gi1; };
layout(std430, binding = 1) readonly buffer Counters { GpuGi1Counters counters; };
layout(std430, binding = 2) readonly buffer Touched { uint touched[]; };
layout(std430, binding = 3) buffer CacheMax { uint cache_max[]; };
layout(std430, binding = 4) buffer CacheSums { uvec4 cache_sums[]; };
// Per tile, its 85 cells (gi1_hash.glsl): rgb the cached radiance, w the samples behind it.
layout(std430, binding = 5) buffer CacheCells { vec4 cache_cells[]; };

#include "techniques/gi1/gi1_dispatch.glsl"
#include "techniques/gi1/gi1_cache_tile.glsl"

shared vec4 level[GIQ_GI1_TILE_CELLS];

void main() {
  uint g = gi1_group();
  if (g >= counters.tile_groups.w) return;
  uint tile = touched[g], lane = gl_LocalInvocationIndex;
  uint cell = tile * GIQ_GI1_CELLS + lane;
  uvec4 sums = cache_sums[cell];
  vec4 v = cache_cells[tile * GIQ_GI1_TILE_CELLS + lane];
  if (sums.w > 0u) {
    float k = float(min(sums.w, GIQ_GI1_MAX_CELL_SAMPLES));
    vec3 mean = vec3(sums.xyz) * (uintBitsToFloat(cache_max[cell]) / (GIQ_GI1_QUANTUM * k));
    float n = min(v.w + k, float(gi1.cache.w));
    v.rgb += (mean - v.rgb) * min(1.0, k / n);
    v.w = n;
    cache_cells[tile * GIQ_GI1_TILE_CELLS + lane] = v;
    cache_sums[cell] = uvec4(0u);
    cache_max[cell] = 0u;
  }
  level[lane] = v;
  barrier();
  // Levels 1 to 3 (4x4, 2x2, 1x1) from the level above, each cell from its 2x2 children.
  for (uint l = 1u; l <= 3u; ++l) {
    uint side = GIQ_GI1_TILE >> l, above = gi1_tile_level_offset(l - 1u), first = gi1_tile_level_offset(l);
    if (lane < side * side) {
      uvec2 xy = uvec2(lane % side, lane / side) * 2u;
      vec4 sum = vec4(0.0);
      for (uint j = 0u; j < 4u; ++j) {
        vec4 child = level[above + (xy.x + (j & 1u)) + (xy.y + (j >> 1u)) * side * 2u];
        sum += vec4(child.rgb * child.w, child.w);
      }
      vec4 mip = vec4(sum.w > 0.0 ? sum.rgb / sum.w : vec3(0.0), sum.w);
      level[first + lane] = mip;
      cache_cells[tile * GIQ_GI1_TILE_CELLS + first + lane] = mip;
    }
    barrier();
  }
}
