#version 460
// `gi1`: where new probes spawn this frame (Boissé et al. 2022, section 2.1.1). A
// spawn tile is upscale x upscale screen tiles; each frame one of them, on this frame's
// jittered pixel, gets a new probe, so that every tile gets one every upscale^2 frames (1/4
// sample per pixel at the default 2 x 2). Per tile: the pixel it spawns on, or none, and the
// pixel an empty tile would spawn on if rays are moved to it (gi1_patch.comp).
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/surface.glsl"
#include "shaders/sampling.glsl"
#include "techniques/gi1/gi1_shared.h"

layout(local_size_x = 64) in;

#include "passes/receiver.glsl"
#include "techniques/gi1/gi1_common.glsl"
// Per tile: x the pixel it spawns on, y the pixel it would spawn on (GIQ_GI1_NONE: none).
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 0) writeonly buffer Spawn { uvec2 spawn[]; };

#include "techniques/gi1/gi1_probe.glsl"

void main() {
  uint t = gl_GlobalInvocationID.x;
  if (t >= gi1.size.z * gi1.size.w) return;
  uvec2 tile = uvec2(t % gi1.size.z, t / gi1.size.z);
  uvec2 px = tile * GIQ_GI1_PROBE + gi1_unpack_pixel(gi1.jitter.x);
  uint candidate = GIQ_GI1_NONE;
  if (all(lessThan(px, gi1.size.xy)) && load_receiver(ivec2(px)).lit) candidate = gi1_pack_pixel(px);
  bool chosen = all(equal(tile % gi1.spawn.xy, gi1_unpack_pixel(gi1.jitter.y)));
  spawn[t] = uvec2(chosen ? candidate : GIQ_GI1_NONE, candidate);
}
