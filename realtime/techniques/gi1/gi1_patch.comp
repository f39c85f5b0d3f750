#version 460
// `gi1`: the list of probes to trace this frame, and temporal adaptive sampling
// (Boissé et al. 2022, section 2.1.2, Algorithm 2): rays move from spawned tiles that also
// have last frame's probe (override tiles) to tiles that have neither (empty tiles), so that
// disocclusions fill fast while the frame's ray count stays the same. One work group walks
// the tiles in order, so the lists, and the frame, are the same on every run: where the
// report lets each empty tile take a random override tile with an atomic exchange (two may
// take the same one, and which wins depends on timing), empty tile i here takes override
// tile (i * s + o) mod O, s prime to O and o random per frame: as scattered, no two empty
// tiles take the same one, and nothing depends on timing.
#extension GL_GOOGLE_include_directive : require

#include "techniques/gi1/gi1_shared.h"

layout(local_size_x = 1024) in;

layout(std430, binding = 0) readonly buffer Frame { GpuGi1Frame gi1; };
layout(std430, binding = 1) buffer Probes { GpuGi1Probe probes[]; };
layout(std430, binding = 2) buffer Spawn { uvec2 spawn[]; };
layout(std430, binding = 3) buffer Counters { GpuGi1Counters counters; };
layout(std430, binding = 4) buffer SpawnList { uint spawn_list[]; };
// Scratch, one entry per tile: override tiles (as their place in the spawn list), empty tiles.
layout(std430, binding = 5) buffer Overrides { uint overrides[]; };
layout(std430, binding = 6) buffer Empties { uint empties[]; };

#include "shaders/sampling.glsl"
#include "techniques/gi1/gi1_probe.glsl"
#include "techniques/gi1/gi1_dispatch.glsl"

shared uvec3 scan[1024];

// A prime; k * kStride stays within 32 bits for the million tiles of an 8K image.
const uint kStride = 4099u;

void main() {
  uint i = gl_LocalInvocationIndex;
  uint n = gi1.size.z * gi1.size.w;
  uint chunk = (n + 1023u) / 1024u, first = min(n, i * chunk), last = min(n, first + chunk);
  bool adaptive = (gi1.counts.w & GIQ_GI1_ADAPTIVE_SAMPLING) != 0u;
  // x spawned, y override, z empty
  uvec3 mine = uvec3(0u);
  for (uint t = first; t < last; ++t) {
    uvec2 s = spawn[t];
    bool reprojected = (probes[t].info.y & GIQ_GI1_REPROJECTED) != 0u;
    if (s.x != GIQ_GI1_NONE) mine += uvec3(1u, reprojected ? 1u : 0u, 0u);
    else if (!reprojected && s.y != GIQ_GI1_NONE) mine.z += 1u;
  }
  scan[i] = mine;
  barrier();
  for (uint step = 1u; step < 1024u; step <<= 1u) {  // inclusive prefix sums (Hillis and Steele)
    uvec3 add = i >= step ? scan[i - step] : uvec3(0u);
    barrier();
    scan[i] += add;
    barrier();
  }
  uvec3 total = scan[1023];
  uvec3 at = scan[i] - mine;
  for (uint t = first; t < last; ++t) {
    uvec2 s = spawn[t];
    bool reprojected = (probes[t].info.y & GIQ_GI1_REPROJECTED) != 0u;
    if (s.x != GIQ_GI1_NONE) {
      if (reprojected) overrides[at.y++] = at.x;
      spawn_list[at.x++] = t;
    } else if (!reprojected && s.y != GIQ_GI1_NONE) {
      empties[at.z++] = t;
    }
  }
  memoryBarrierBuffer();
  barrier();
  uint moved = adaptive ? min(total.y, total.z) : 0u;
  if (moved > 0u) {
    uint stride = total.y % kStride == 0u ? 1u : kStride;
    uint offset = pcg_hash(gi1.jitter.z ^ gi1_stream(gi1, 4u)) % total.y;
    for (uint k = i; k < moved; k += 1024u) {
      uint e = empties[k];
      uint place = overrides[(k * stride % total.y + offset) % total.y];
      uint from = spawn_list[place];
      spawn[from].x = GIQ_GI1_NONE;  // keeps its reprojected probe
      spawn[e].x = spawn[e].y;
      probes[e].info.y |= GIQ_GI1_PATCHED;
      spawn_list[place] = e;
    }
  }
  if (i == 0u) {
    counters.probe_groups = gi1_groups(total.x);
    counters.tiles = uvec4(total.z - moved, moved, 0u, 0u);
  }
}
