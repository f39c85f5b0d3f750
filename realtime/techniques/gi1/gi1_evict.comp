#version 460
// `gi1`: world-cache tiles that no ray reached for `decay` frames are freed (Boissé
// et al. 2022, section 2.2.1), their cells cleared for the next key that claims the slot.
// When lights or geometry moved, every live cell's sample count drops to a quarter of its cap,
// so that the next samples move it four times as fast (the cache follows the change without
// forgetting what is still right).
#extension GL_GOOGLE_include_directive : require

#include "techniques/gi1/gi1_shared.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) buffer CacheHash { uint cache_hash[]; };
layout(std430, binding = 1) buffer CacheStamp { uint cache_stamp[]; };
layout(std430, binding = 2) buffer CacheCells { vec4 cache_cells[]; };

layout(push_constant) uniform Push {
  uint tiles;   // tile slots
  uint frame;
  uint decay;   // frames an unused tile lives
  float react;  // > 0: the scene changed; the sample count every cell is capped at
} pc;

void main() {
  uint t = gl_GlobalInvocationID.x;
  if (t >= pc.tiles || cache_hash[t] == 0u) return;
  uint first = t * GIQ_GI1_TILE_CELLS;
  if (pc.frame + 1u - cache_stamp[t] >= pc.decay) {
    cache_hash[t] = 0u;
    cache_stamp[t] = 0u;
    for (uint c = 0u; c < GIQ_GI1_TILE_CELLS; ++c) cache_cells[first + c] = vec4(0.0);
  } else if (pc.react > 0.0) {
    for (uint c = 0u; c < GIQ_GI1_TILE_CELLS; ++c) cache_cells[first + c].w = min(cache_cells[first + c].w, pc.react);
  }
}
