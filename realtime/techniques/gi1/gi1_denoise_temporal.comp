#version 460
// `gi1`: the denoiser's temporal accumulation (Boissé et al. 2022, section 2.4.3).
// Each pixel's irradiance is blended with its history, read where its surface was last frame
// (the motion vectors; bilinear taps, each kept where last frame's surface there lies within
// half a cell of this point's depth in the previous view), by a moving average over up to
// `denoise_history` frames that is the plain mean while the history is short. A relaxed
// interpolation (gi1_interpolate.comp) is discarded where there is history (the report's
// hint to the denoiser). Output: irradiance and view depth (also last frame's irradiance for
// the probe rays' feedback, gi1_trace.comp) and the history length.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/surface.glsl"
#include "shaders/sampling.glsl"
#include "techniques/gi1/gi1_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

#include "passes/receiver.glsl"
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 0) readonly buffer Frame { GpuGi1Frame gi1; };
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 1, rgba32f) uniform readonly image2D gb_motion;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 2, rgba32f) uniform readonly image2D raw;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 3, rgba32f) uniform readonly image2D previous_irradiance;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 4, r32f) uniform readonly image2D previous_length;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 5, rgba32f) uniform writeonly image2D out_irradiance;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 6, r32f) uniform writeonly image2D out_length;

#include "techniques/gi1/gi1_probe.glsl"

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), gi1.size.xy))) return;
  vec4 e = imageLoad(raw, px);
  if (e.w < 0.0) {
    imageStore(out_irradiance, px, vec4(0.0, 0.0, 0.0, -1.0));
    imageStore(out_length, px, vec4(0.0));
    return;
  }
  Receiver r = load_receiver(px);
  float depth = gi1_view_depth(gi1.camera, r.x);
  vec3 history = vec3(0.0);
  float length_ = 0.0, total = 0.0;
  vec4 motion = imageLoad(gb_motion, px);
  if ((gi1.counts.w & GIQ_GI1_HISTORY) != 0u && motion.w > 0.0 && gi1.params.z > 0.0) {
    float expected = gi1_view_depth(gi1.previous, r.x);
    vec2 q = vec2(px) + motion.xy;  // + 0.5 - 0.5: the taps' centres
    ivec2 base = ivec2(floor(q));
    vec2 w = q - vec2(base);
    for (int j = 0; j < 4; ++j) {
      ivec2 o = ivec2(j & 1, j >> 1), t = base + o;
      if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, ivec2(gi1.size.xy)))) continue;
      vec4 h = imageLoad(previous_irradiance, t);
      if (!gi1_seen_last_frame(gi1, h.w, expected, 0.5)) continue;
      float weight = (o.x == 1 ? w.x : 1.0 - w.x) * (o.y == 1 ? w.y : 1.0 - w.y);
      history += weight * h.rgb;
      length_ += weight * imageLoad(previous_length, t).x;
      total += weight;
    }
  }
  vec3 result = e.rgb;
  float n = 1.0;
  if (total > 0.0) {
    history /= total;
    length_ /= total;
    if (e.w > 0.0) {  // relaxed: keep the history
      result = history;
      n = length_;
    } else {
      n = min(length_ + 1.0, gi1.params.z);
      result = mix(history, e.rgb, 1.0 / n);
    }
  }
  imageStore(out_irradiance, px, vec4(result, depth));
  imageStore(out_length, px, vec4(n));
}
