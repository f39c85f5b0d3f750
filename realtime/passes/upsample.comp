#version 460
// Edge-aware upsample and 9×9 cross-bilateral blur (passes/upsample.h).
#extension GL_GOOGLE_include_directive : require
#include "passes/upsample_shared.h"
#include "passes/low_resolution.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba32f) uniform readonly image2D gb_position;
layout(binding = 1, rgba32f) uniform readonly image2D gb_normal;
layout(binding = 2, rgba32f) uniform readonly image2D src;
layout(binding = 3, rgba32f) uniform writeonly image2D dst;
layout(push_constant) uniform Push { UpsamplePush pc; };

// How much the surface at (q_pos, q_n) resembles the receiver (p_pos, p_n), in [0, 1]:
// normals must agree (the cosine to the 32nd power halves at 12 degrees) and q must lie near
// p's tangent plane, measured as the sine of the angle between p->q and that plane, so the
// weight is the same at any scene scale and distance.
float geometric_weight(vec4 p_pos, vec3 p_n, vec4 q_pos, vec3 q_n) {
  if (q_pos.w == 0.0) return 0.0;  // q sees the background
  float wn = pow(max(dot(p_n, q_n), 0.0), 32.0);
  vec3 d = q_pos.xyz - p_pos.xyz;
  float len2 = dot(d, d);
  float s = len2 > 0.0 ? abs(dot(p_n, d)) * inversesqrt(len2) : 0.0;
  return wn * exp(-(s * s) / (0.1 * 0.1));
}

ivec2 full_of_low(ivec2 q) { return full_resolution_pixel(q, int(pc.factor), ivec2(pc.size)); }

vec4 upsample(ivec2 px, vec4 p_pos, vec3 p_n) {
  int k = int(pc.factor);
  ivec2 low_size = imageSize(src);
  // The low samples left of/above and right of/below this pixel, and where they stand in
  // full-resolution pixels (the last one is clamped to the border, so spacing is not always k).
  vec2 u = (vec2(px) - float(k / 2)) / float(k);
  ivec2 base = ivec2(floor(u));
  ivec2 q0 = clamp(base, ivec2(0), low_size - 1), q1 = clamp(base + 1, ivec2(0), low_size - 1);
  vec2 s0 = vec2(full_of_low(q0)), s1 = vec2(full_of_low(q1));
  vec2 f = clamp((vec2(px) - s0) / max(s1 - s0, vec2(1.0)), 0.0, 1.0);
  vec4 sum = vec4(0.0);
  float wsum = 0.0;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      ivec2 q = ivec2(i == 0 ? q0.x : q1.x, j == 0 ? q0.y : q1.y);
      float wb = (i == 0 ? 1.0 - f.x : f.x) * (j == 0 ? 1.0 - f.y : f.y);
      ivec2 g = full_of_low(q);
      float w = wb * geometric_weight(p_pos, p_n, imageLoad(gb_position, g), imageLoad(gb_normal, g).xyz);
      sum += w * imageLoad(src, q);
      wsum += w;
    }
  if (wsum > 1e-4) return sum / wsum;
  // No bilinear neighbour lies on this surface (a thin object, a corner): the most similar
  // sample of the 4×4 neighbourhood, or the nearest one if none is similar at all.
  float best = -1.0;
  vec4 pick = imageLoad(src, clamp(ivec2(round(u)), ivec2(0), low_size - 1));
  for (int j = -1; j <= 2; ++j)
    for (int i = -1; i <= 2; ++i) {
      ivec2 q = clamp(base + ivec2(i, j), ivec2(0), low_size - 1);
      ivec2 g = full_of_low(q);
      float w = geometric_weight(p_pos, p_n, imageLoad(gb_position, g), imageLoad(gb_normal, g).xyz);
      if (w > best && w > 0.0) {
        best = w;
        pick = imageLoad(src, q);
      }
    }
  return pick;
}

const float kBinomial[5] = float[5](70.0, 56.0, 28.0, 8.0, 1.0);

vec4 blur(ivec2 px, vec4 p_pos, vec3 p_n, ivec2 axis) {
  ivec2 size = ivec2(pc.size);
  vec4 sum = kBinomial[0] * imageLoad(src, px);
  float wsum = kBinomial[0];
  for (int t = 1; t <= 4; ++t)
    for (int side = -1; side <= 1; side += 2) {
      ivec2 q = px + side * t * axis;
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
      float w = kBinomial[t] * geometric_weight(p_pos, p_n, imageLoad(gb_position, q), imageLoad(gb_normal, q).xyz);
      sum += w * imageLoad(src, q);
      wsum += w;
    }
  return sum / wsum;
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), pc.size))) return;
  vec4 p_pos = imageLoad(gb_position, px);
  if (p_pos.w == 0.0) {  // background: nothing to light
    imageStore(dst, px, vec4(0.0, 0.0, 0.0, 1.0));
    return;
  }
  vec3 p_n = imageLoad(gb_normal, px).xyz;
  vec4 v;
  if (pc.mode == GIQ_UPSAMPLE_MODE_UPSAMPLE)
    v = pc.factor == 1u ? imageLoad(src, px) : upsample(px, p_pos, p_n);
  else
    v = blur(px, p_pos, p_n, pc.mode == GIQ_UPSAMPLE_MODE_BLUR_X ? ivec2(1, 0) : ivec2(0, 1));
  imageStore(dst, px, vec4(v.rgb, 1.0));
}
