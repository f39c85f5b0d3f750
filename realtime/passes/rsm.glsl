// Encoding of a reflective-shadow-map texel (passes/rsm.h): RGBA32UI holds the VPL's position
// (three float32 bit patterns) and its unit normal (octahedral, two 16-bit snorms; Cigolle et
// al. 2014, "A Survey of Efficient Representations for Independent Unit Vectors"); RGBA16F
// holds its flux density times the layer's flux scale.
#ifndef GIQ_RSM_GLSL
#define GIQ_RSM_GLSL

vec2 rsm_oct_wrap(vec2 v) { return (1.0 - abs(v.yx)) * vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }

uint rsm_encode_normal(vec3 n) {
  n /= abs(n.x) + abs(n.y) + abs(n.z);
  vec2 e = n.z >= 0.0 ? n.xy : rsm_oct_wrap(n.xy);
  return packSnorm2x16(e);
}

vec3 rsm_decode_normal(uint bits) {
  vec2 e = unpackSnorm2x16(bits);
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (n.z < 0.0) n.xy = rsm_oct_wrap(n.xy);
  return normalize(n);
}

uvec4 rsm_encode_surface(vec3 p, vec3 n) { return uvec4(floatBitsToUint(p), rsm_encode_normal(n)); }

#endif
