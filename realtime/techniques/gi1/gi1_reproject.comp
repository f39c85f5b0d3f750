#version 460
// `gi1`: last frame's screen probes follow the motion vectors onto this frame's pixels (Boissé et
// al. 2022, Algorithm 1). Each tile is a work group; each of its pixels looks up, where it was last
// frame, the probe of the tile it was in, and offers itself as that probe's new place when the
// probe lies within a cell size of its plane and their normals agree (cosine > 0.95); the closest
// offer wins (packed distance and lane, one atomic minimum). A pixel whose point last frame's
// image did not show (its depth there off by more than half a cell: it was hidden) offers
// nothing, the disocclusion test Algorithm 1 leaves to the motion vectors.
// The winner carries the probe's radiance, its spherical harmonics and its normal (the frame its
// cells are in) into this tile; a tile nobody offers is empty until a probe is spawned on it.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/surface.glsl"
#include "shaders/sampling.glsl"
#include "techniques/gi1/gi1_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

#include "passes/receiver.glsl"
#include "techniques/gi1/gi1_common.glsl"
layout(binding = GIQ_GI1_BINDING_COUNT + 0, rgba32f) uniform readonly image2D gb_motion;
// Last frame's irradiance and view depth per pixel (gi1_denoise_temporal.comp): w is the depth
// of the surface that pixel showed, -1 where none.
layout(binding = GIQ_GI1_BINDING_COUNT + 1, rgba32f) uniform readonly image2D previous_irradiance;

#include "techniques/gi1/gi1_probe.glsl"

shared uint best;
shared uint source;

void main() {
  uvec2 tile = gl_WorkGroupID.xy;
  uint lane = gl_LocalInvocationIndex;
  ivec2 px = ivec2(tile * GIQ_GI1_PROBE + gl_LocalInvocationID.xy);
  if (lane == 0u) best = 0xffffffffu;
  barrier();
  uint t = gi1_tile_index(tile);
  bool inside = all(lessThan(uvec2(px), gi1.size.xy));
  Receiver r;
  r.lit = false;
  uint from = GIQ_GI1_NONE;
  if (inside && (gi1.counts.w & GIQ_GI1_HISTORY) != 0u) r = load_receiver(px);
  if (r.lit) {
    vec4 motion = imageLoad(gb_motion, px);
    vec2 q = vec2(px) + 0.5 + motion.xy;
    // Disocclusion: the pixel's point must be what last frame's pixel there showed (its depth
    // in the previous view within half a cell), or it was hidden and no probe saw it.
    float seen = motion.w > 0.0 ? imageLoad(previous_irradiance, ivec2(q)).w : -1.0;
    bool visible = gi1_seen_last_frame(gi1, seen, gi1_view_depth(gi1.previous, r.x), 0.5);
    if (visible && all(greaterThanEqual(q, vec2(0.0))) && all(lessThan(q, vec2(gi1.size.xy)))) {
      from = gi1_tile_index(uvec2(q) / GIQ_GI1_PROBE);
      GpuGi1Probe p = previous_probes[from];
      float cell = gi1_screen_cell(gi1, gi1_view_depth(gi1.camera, r.x));
      float plane = abs(dot(p.position.xyz - r.x, r.n));
      if (p.info.x != GIQ_GI1_NONE && plane < cell && dot(p.normal.xyz, r.n) > 0.95) {
        // The distance in cell sizes, so that half precision orders it at every scale.
        float d = min(distance(p.position.xyz, r.x) / cell, 65504.0);
        atomicMin(best, (packHalf2x16(vec2(d, 0.0)) << 16) | lane);
      }
    }
  }
  barrier();
  if (best != 0xffffffffu && lane == (best & 0xffffu)) {
    source = from;
    GpuGi1Probe p = previous_probes[from];
    GpuGi1Probe n;
    n.info = uvec4(gi1_pack_pixel(uvec2(px)), GIQ_GI1_REPROJECTED, from, 0u);
    n.position = vec4(r.x, gi1_view_depth(gi1.camera, r.x));
    n.normal = vec4(p.normal.xyz, gi1_screen_cell(gi1, n.position.w));
    probes[t] = n;
  }
  if (best == 0xffffffffu && lane == 0u) {
    GpuGi1Probe n;
    n.info = uvec4(GIQ_GI1_NONE, 0u, GIQ_GI1_NONE, 0u);
    n.position = vec4(0.0);
    n.normal = vec4(0.0);
    probes[t] = n;
  }
  barrier();
  if (best == 0xffffffffu) return;
  radiance[t * GIQ_GI1_CELLS + lane] = previous_radiance[source * GIQ_GI1_CELLS + lane];
  if (lane < GIQ_GI1_SH) harmonics[t * GIQ_GI1_SH + lane] = previous_harmonics[source * GIQ_GI1_SH + lane];
}
