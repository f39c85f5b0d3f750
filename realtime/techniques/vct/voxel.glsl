// Voxel texels: 8-bit sRGB-encoded premultiplied radiance (scaled into [0, 1]) and linear
// 8-bit opacity, packed into one uint so that the same texel is written through an R32_UINT
// storage view and read back, decoded and filtered, through an R8G8B8A8_SRGB view
// (techniques/vct/volume.h). The sRGB transfer function is IEC 61966-2-1's, which is what the
// sampler inverts.
#ifndef GIQ_VCT_VOXEL_GLSL
#define GIQ_VCT_VOXEL_GLSL

float srgb_encode(float x) {
  x = clamp(x, 0.0, 1.0);
  return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}

float srgb_decode(float x) { return x <= 0.04045 ? x / 12.92 : pow((x + 0.055) / 1.055, 2.4); }

uint pack_voxel(vec4 v) {
  uvec4 q = uvec4(round(vec4(srgb_encode(v.r), srgb_encode(v.g), srgb_encode(v.b), clamp(v.a, 0.0, 1.0)) * 255.0));
  return q.r | (q.g << 8) | (q.b << 16) | (q.a << 24);
}

vec4 unpack_voxel(uint p) {
  vec4 q = vec4(uvec4(p, p >> 8, p >> 16, p >> 24) & 0xffu) / 255.0;
  return vec4(srgb_decode(q.r), srgb_decode(q.g), srgb_decode(q.b), q.a);
}

#endif
