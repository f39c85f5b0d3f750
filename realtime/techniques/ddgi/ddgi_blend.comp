#version 460
// `ddgi`'s probe update (Majercik et al. 2019, the probe update): one workgroup per
// probe, one invocation per interior texel of its octahedral tile. Each texel gathers the
// frame's blended rays (not the fixed ones) with weight max(0, d.r) for irradiance, or
// max(0, d.r)^50 for the distance moments (mean and mean square of the hit distance, capped
// at GpuDdgiVolume::bias.z), and mixes the result into the texel with the hysteresis.
//   Irradiance: E = pi sum(w L) / sum(w), the cosine-weighted mean radiance times pi (the
//   Monte Carlo estimate of the integral over the hemisphere, normalised by the weights' own
//   sum), stored as E^(1/gamma) (the papers' perceptual encoding, gamma = 5) and blended in
//   that space as the papers do. A large change (relative to the texel's own encoded value,
//   so that the thresholds do not depend on the scene's light units) lowers the hysteresis by
//   0.75, and a change beyond the brightness threshold is cut to a quarter (RTXGI's handling of
//   light switched on or off, and of fireflies).
//   Distance: back faces count at a fifth of their distance, so that a probe inside geometry
//   sees its walls close and the Chebyshev test rejects it (RTXGI's convention).
// The first frame has no history; until a texel has 1 / (1 - hysteresis) frames of history
// it keeps their plain mean (hysteresis min(h, 1 - 1/(frames + 1))), so a static scene
// converges from black in about that many frames instead of approaching it exponentially.
#extension GL_GOOGLE_include_directive : require

#include "shaders/sampling.glsl"
#include "techniques/ddgi/ddgi_shared.h"

#ifndef GIQ_DDGI_TEXELS
#error GIQ_DDGI_TEXELS: the interior texels of a tile
#endif
layout(local_size_x = GIQ_DDGI_TEXELS, local_size_y = GIQ_DDGI_TEXELS) in;

layout(std430, binding = 0) readonly buffer Volume { GpuDdgiVolume ddgi; };
layout(std430, binding = 1) readonly buffer Probes { GpuDdgiProbe ddgi_probes[]; };
layout(std430, binding = 2) readonly buffer Rays { vec4 rays[]; };
#ifdef GIQ_DDGI_DISTANCE
layout(binding = 3, rg32f) uniform image2D atlas;
#else
layout(binding = 3, rgba32f) uniform image2D atlas;
#endif
// Frames of history per probe (ddgi_probes.comp counts them).
layout(std430, binding = 4) readonly buffer History { uint history[]; };

layout(push_constant) uniform Push { DdgiBlendPush pc; };

#define GIQ_DDGI_NO_SAMPLERS
#include "techniques/ddgi/ddgi_volume.glsl"

void main() {
  uint probe = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
  if (probe >= ddgi.counts.w || !ddgi_probe_active(probe)) return;
  const uint n = GIQ_DDGI_TEXELS;
  uvec2 t = gl_LocalInvocationID.xy;
  vec3 dir = oct_texel_direction(t, n);
  uint count = ddgi.tiles.w;
  uint base = probe * count;
#ifdef GIQ_DDGI_DISTANCE
  vec2 sum = vec2(0.0);
#else
  vec3 sum = vec3(0.0);
#endif
  float weights = 0.0;
  for (uint r = GIQ_DDGI_FIXED_RAYS; r < count; ++r) {
    vec4 ray = rays[base + r];
    float w = max(0.0, dot(dir, ddgi_ray_direction(r, pc.rotation)));
#ifdef GIQ_DDGI_DISTANCE
    w = pow(w, 50.0);
    if (w <= 0.0) continue;
    float d = min(ray.w < 0.0 ? -0.2 * ray.w : ray.w, ddgi.bias.z);
    sum += w * vec2(d, d * d);
#else
    if (w <= 0.0) continue;
    sum += w * ray.rgb;
#endif
    weights += w;
  }
  ivec2 texel = ivec2(oct_tile_origin(probe, n, ddgi.tiles.x) + 1u + t);
  uint frames = history[probe];
  float h = min(pc.hysteresis, 1.0 - 1.0 / float(frames + 1u));  // 0 without history
#ifdef GIQ_DDGI_DISTANCE
  vec2 result = weights > 0.0 ? sum / weights : vec2(0.0);
  vec2 previous = imageLoad(atlas, texel).xy;
  imageStore(atlas, texel, vec4(mix(result, previous, h), 0.0, 0.0));
#else
  vec3 result = weights > 0.0 ? PI * sum / weights : vec3(0.0);
  result = pow(max(result, vec3(0.0)), vec3(1.0 / ddgi.bias.w));
  vec3 previous = imageLoad(atlas, texel).rgb;
  if (h > 0.0) {
    vec3 delta = result - previous;
    float scale = max(max(previous.r, max(previous.g, previous.b)), max(result.r, max(result.g, result.b)));
    float change = scale > 0.0 ? max(abs(delta.r), max(abs(delta.g), abs(delta.b))) / scale : 0.0;
    if (change > pc.change_threshold) h = max(0.0, h - 0.75);
    if (change > pc.brightness_threshold) result = previous + delta * 0.25;
  }
  imageStore(atlas, texel, vec4(mix(result, previous, h), 1.0));
#endif
}
