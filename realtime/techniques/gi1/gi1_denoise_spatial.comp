#version 460
// `gi1`: the denoiser's spatial filter (Boissé et al. 2022, section 2.4.3): a 5x5
// edge-aware blur whose radius shrinks as the history grows, denoise_radius / n pixels for
// the shortest history n in the pixel's 3x3 neighbourhood (the report's blur mask: the
// disocclusion mask, dilated), so that new pixels are smoothed hard and converged ones not at
// all. Taps weigh by a Gaussian, by how well their normals agree and by their distance from
// the pixel's plane, zero beyond half a cell. Output: the indirect light, diffuse albedo / pi
// x irradiance.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/brdf.glsl"
#include "shaders/surface.glsl"
#include "shaders/sampling.glsl"
#include "passes/rsm_albedo.glsl"
#include "techniques/gi1/gi1_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

#include "passes/receiver.glsl"
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 0) readonly buffer Frame { GpuGi1Frame gi1; };
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 1, rgba32f) uniform readonly image2D irradiance;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 2, r32f) uniform readonly image2D history_length;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 3, rgba32f) uniform writeonly image2D out_indirect;

#include "techniques/gi1/gi1_probe.glsl"

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), gi1.size.xy))) return;
  vec4 e = imageLoad(irradiance, px);
  if (e.w < 0.0) {
    imageStore(out_indirect, px, vec4(0.0, 0.0, 0.0, 1.0));
    return;
  }
  Receiver r = load_receiver(px);
  float shortest = 1e30;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      ivec2 q = px + ivec2(x, y);
      bool inside = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, ivec2(gi1.size.xy)));
      if (inside && imageLoad(irradiance, q).w >= 0.0)
        shortest = min(shortest, imageLoad(history_length, q).x);
    }
  float radius = gi1.params.w / max(shortest, 1.0);
  vec3 sum = e.rgb;
  float total = 1.0;
  if (radius >= 1.0) {
    float tolerance = 0.5 * gi1_screen_cell(gi1, e.w);
    for (int y = -2; y <= 2; ++y)
      for (int x = -2; x <= 2; ++x) {
        if (x == 0 && y == 0) continue;
        ivec2 q = px + ivec2(round(vec2(x, y) * 0.5 * radius));
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(gi1.size.xy)))) continue;
        vec4 eq = imageLoad(irradiance, q);
        if (eq.w < 0.0) continue;
        vec3 nq = imageLoad(gb_normal, q).xyz;
        float plane = abs(dot(imageLoad(gb_position, q).xyz - r.x, r.n));
        float w = exp(-0.5 * float(x * x + y * y)) * pow(max(dot(nq, r.n), 0.0), 8.0) *
                  max(0.0, 1.0 - plane / tolerance);
        sum += w * eq.rgb;
        total += w;
      }
  }
  imageStore(out_indirect, px, vec4(diffuse_albedo(receiver_surface(r)) / PI * (sum / total), 1.0));
}
