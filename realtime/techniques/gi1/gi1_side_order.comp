#version 460
// `gi1`: the side cache's LRU order (Boissé et al. 2022, section 2.1.8), reordered once a frame:
// the entries used this frame (stamped by the reconstruction and the blend) move to the
// front, the others keep their order behind them, so the least recently used fall to the back,
// where new entries are made. One work group, a stable partition by a prefix sum over the
// order in chunks of it: the same on every run.
#extension GL_GOOGLE_include_directive : require

#include "techniques/gi1/gi1_shared.h"

layout(local_size_x = 1024) in;

layout(std430, binding = 0) readonly buffer Frame { GpuGi1Frame gi1; };
layout(std430, binding = 1) readonly buffer SideState { uint side_state[]; };
layout(std430, binding = 2) readonly buffer Order { uint order[]; };  // this frame's, by rank
layout(std430, binding = 3) writeonly buffer NextOrder { uint next_order[]; };
layout(std430, binding = 4) writeonly buffer SideRank { uint side_rank[]; };

#include "techniques/gi1/gi1_side.glsl"

shared uint used_before[1024];  // per chunk: the used entries in it and the chunks before it
shared uint total_used;

void main() {
  uint i = gl_LocalInvocationIndex, n = gi1.side.x;
  uint chunk = (n + 1023u) / 1024u, first = min(n, i * chunk), last = min(n, first + chunk);
  uint used = 0u;
  for (uint k = first; k < last; ++k) used += side_state[gi1_side_stamp(order[k])] == gi1.side.y ? 1u : 0u;
  used_before[i] = used;
  barrier();
  // An inclusive scan over the chunks in log2(1024) steps (Hillis and Steele 1986).
  for (uint step = 1u; step < 1024u; step <<= 1) {
    uint add = i >= step ? used_before[i - step] : 0u;
    barrier();
    used_before[i] += add;
    barrier();
  }
  if (i == 1023u) total_used = used_before[1023];
  barrier();
  uint before = used_before[i] - used;  // exclusive
  uint front = before, back = total_used + (first - before);
  for (uint k = first; k < last; ++k) {
    uint e = order[k];
    uint rank = side_state[gi1_side_stamp(e)] == gi1.side.y ? front++ : back++;
    next_order[rank] = e;
    side_rank[e] = rank;
  }
}
