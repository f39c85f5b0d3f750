#version 460
// `pt`: progressive path tracer with the reference's light transport (shaders/path.glsl),
// every punctual light sampled at every vertex. Samples accumulate across frames; the outputs
// are the running means: direct (emission seen directly plus light reaching the first surface
// after one reflection), indirect (the rest), their sum, and the variance of the mean.
#extension GL_GOOGLE_include_directive : require

#include "shaders/bvh.glsl"
#include "shaders/brdf.glsl"
#include "shaders/surface.glsl"
#include "shaders/camera.glsl"
#include "shaders/lights.glsl"
#include "shaders/environment.glsl"
#include "shaders/path.glsl"
#include "pt_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = GIQ_SCENE_BINDING_COUNT + 0, rgba32f) uniform image2D accum_direct;
layout(binding = GIQ_SCENE_BINDING_COUNT + 1, rgba32f) uniform image2D accum_indirect;
layout(binding = GIQ_SCENE_BINDING_COUNT + 2, rgba32f) uniform image2D accum_square;
layout(binding = GIQ_SCENE_BINDING_COUNT + 3, rgba32f) uniform writeonly image2D out_beauty;
layout(binding = GIQ_SCENE_BINDING_COUNT + 4, rgba32f) uniform writeonly image2D out_direct;
layout(binding = GIQ_SCENE_BINDING_COUNT + 5, rgba32f) uniform writeonly image2D out_indirect;
layout(binding = GIQ_SCENE_BINDING_COUNT + 6, rgba32f) uniform writeonly image2D out_variance;

layout(push_constant) uniform Push { PtPush pc; };

void main() {
  uvec2 px = gl_GlobalInvocationID.xy;
  if (px.x >= pc.width || px.y >= pc.height) return;
  ivec2 ip = ivec2(px);
  vec4 sum_d = pc.first_sample == 0u ? vec4(0.0) : imageLoad(accum_direct, ip);
  vec4 sum_i = pc.first_sample == 0u ? vec4(0.0) : imageLoad(accum_indirect, ip);
  vec4 sum_sq = pc.first_sample == 0u ? vec4(0.0) : imageLoad(accum_square, ip);
  vec2 size = vec2(pc.width, pc.height);
  PathParams params = PathParams(pc.environment, pc.max_bounces, pc.light_count, pc.emissive_count);
  for (uint k = 0u; k < pc.samples_per_frame; ++k) {
    uint sample_index = pc.first_sample + k;
    Rng rng = rng_init(px, sample_index, pc.seed);
    // A uniformly jittered position in the pixel: the box filter of the reference.
    vec2 pixel = vec2(px) + vec2(rng_next(rng), rng_next(rng));
    vec3 dir = camera_ray_direction(pc.camera, pixel, size);
    PathState r = path_start();
    path_trace(params, r, 0u, camera_ray_origin(pc.camera, pixel, size), dir, rng);
    // A non-finite sample would poison the running mean forever; it can only come from a
    // degenerate configuration, and is dropped (counted as black).
    if (!all(lessThan(abs(r.direct + r.indirect), vec3(3.0e38)))) { r.direct = vec3(0.0); r.indirect = vec3(0.0); }
    sum_d.rgb += r.direct;
    sum_i.rgb += r.indirect;
    vec3 beauty = r.direct + r.indirect;
    sum_sq.rgb += beauty * beauty;
  }
  imageStore(accum_direct, ip, sum_d);
  imageStore(accum_indirect, ip, sum_i);
  imageStore(accum_square, ip, sum_sq);
  float n = float(pc.first_sample + pc.samples_per_frame);
  vec3 mean_d = sum_d.rgb / n, mean_i = sum_i.rgb / n, mean = mean_d + mean_i;
  // Variance of the mean: the unbiased sample variance over n.
  vec3 var = n > 1.0 ? max(sum_sq.rgb / n - mean * mean, vec3(0.0)) * n / (n - 1.0) / n : vec3(0.0);
  imageStore(out_beauty, ip, vec4(mean, 1.0));
  imageStore(out_direct, ip, vec4(mean_d, 1.0));
  imageStore(out_indirect, ip, vec4(mean_i, 1.0));
  imageStore(out_variance, ip, vec4(var, 1.0));
}
