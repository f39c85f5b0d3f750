// `gi1`'s reservoir grid (Boissé et al. 2022, section 2.3.1): light-sampling reservoirs kept in
// world space from one frame to the next, one per cell of a hash grid of the hits' positions,
// quantised as the world cache quantises them (distance-adaptive power-of-two cells,
// gi1_cache_level) but without the direction: the report's "adaptively quantized position of
// the shaded vertex". The grid is direct-mapped: the first hash picks the slot, the second is
// its fingerprint, and a hit whose cell's fingerprint is not in its slot finds no reservoir.
// Needs gi1_hash.glsl.
#ifndef GIQ_GI1_RESERVOIR_GLSL
#define GIQ_GI1_RESERVOIR_GLSL

uint gi1_reservoir_slot(vec3 p, float view_depth, out uint fingerprint) {
  int level = gi1_cache_level(gi1, view_depth);
  vec3 c = clamp(floor(p / exp2(float(level))), vec3(-1073741824.0), vec3(1073741823.0));
  uvec3 u = uvec3(ivec3(c));
  uint words[4] = uint[4](uint(level), u.x, u.y, u.z);
  uint h1 = 0x3c6ef372u, h2 = 0xa54ff53au;
  for (int i = 0; i < 4; ++i) {
    h1 = pcg_hash(h1 ^ words[i]);
    h2 = gi1_fmix(h2 ^ words[i] * 0x27d4eb2fu);
  }
  fingerprint = max(h2, 1u);
  return h1 % gi1.lights.w;
}

#endif
