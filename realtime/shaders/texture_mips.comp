#version 460
// One mip level of one texture from the level above it (SceneGpu, at upload): each texel the
// mean of the 2x2 texels above it (the box filter; for an odd side the last row or column is
// read twice, GL's rounding down of sizes), averaged as decoded floats, so sRGB colour is
// averaged in linear light, and stored in the texture's own format: 8-bit sRGB channels as
// the byte whose decoding is nearest (found in the decode table itself, so decoding it again
// gives the table's float), 8-bit linear channels rounded to the nearest byte, float as is.
#extension GL_GOOGLE_include_directive : require
#define GIQ_TEXTURES 1

#include "shaders/scene.glsl"
#include "shaders/textures.glsl"

layout(buffer_reference, std430, buffer_reference_align = 4) buffer MipWords { uint words[]; };

layout(local_size_x = 8, local_size_y = 8) in;

layout(push_constant) uniform Push {
  uint texture;
  uint level;  // 1 or more: the level written
} pc;

// The byte whose entry in the table at `base` (GIQ_DECODE_SRGB or 0) is nearest to c; the
// entries rise with the byte.
uint encode_byte(float c, uint base) {
  uint lo = 0u, hi = 255u;  // the first byte whose entry is >= c lies in [lo, hi]
  while (lo < hi) {
    uint mid = (lo + hi) >> 1;
    if (scene_decode[base + mid] < c) lo = mid + 1u;
    else hi = mid;
  }
  if (lo > 0u && c - scene_decode[base + lo - 1u] <= scene_decode[base + lo] - c) return lo - 1u;
  return lo;
}

void main() {
  GpuTexture t = scene_textures[pc.texture];
  uvec2 above = mip_size(t, pc.level - 1u), size = mip_size(t, pc.level);
  uvec2 p = gl_GlobalInvocationID.xy;
  if (p.x >= size.x || p.y >= size.y) return;
  uint first = mip_first_texel(t, pc.level - 1u);
  vec4 sum = vec4(0.0);
  for (uint dy = 0u; dy < 2u; ++dy)
    for (uint dx = 0u; dx < 2u; ++dx) {
      uvec2 q = min(2u * p + uvec2(dx, dy), above - 1u);
      sum += texel_word(t, first + q.y * above.x + q.x);
    }
  vec4 mean = sum * 0.25;
  uint i = mip_first_texel(t, pc.level) + p.y * size.x + p.x, format = (t.info.w >> 5) & 3u;
  MipWords out_words = MipWords(t.texels.xy);
  if (format == GIQ_TEXELS_RGBA32F) {
    for (uint c = 0u; c < 4u; ++c) out_words.words[4u * i + c] = floatBitsToUint(mean[c]);
    return;
  }
  uint colour = format == GIQ_TEXELS_RGBA8_SRGB ? GIQ_DECODE_SRGB : 0u;
  out_words.words[i] = encode_byte(mean.r, colour) | encode_byte(mean.g, colour) << 8 |
                       encode_byte(mean.b, colour) << 16 | encode_byte(mean.a, 0u) << 24;
}
