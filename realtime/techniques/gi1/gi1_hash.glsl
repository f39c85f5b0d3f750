// `gi1`'s world cache (Boissé et al. 2022, section 2.2): outgoing radiance at the probe rays'
// hits, in a hash map of tiles of 8x8 cells. A hit's descriptor (its cell size, its tile's
// position, its ray's direction, and whether the ray was shorter than a tile) is hashed twice
// (Jarzynski and Olano 2020): the first hash picks a bucket of `tiles per bucket` tiles, the
// second is the tile's fingerprint, found by linear probing in the bucket (Figure 12). The
// cell within the tile is the hit's position in the two axes across the ray's main axis
// (section 2.2.3: surfaces are flat at a tile's scale).
//
// The includer declares the map: `cache_hash[]` (a tile's fingerprint, 0 for a free tile) and
// `cache_stamp[]` (1 + the frame that last used it), both coherent uint arrays, and reads the
// frame's constants from `gi1` (GpuGi1Frame). Needs shaders/sampling.glsl, gi1_probe.glsl.
#ifndef GIQ_GI1_HASH_GLSL
#define GIQ_GI1_HASH_GLSL

struct Gi1CacheKey {
  uint bucket;       // its bucket
  uint fingerprint;  // never 0 (the free tile's)
  uint cell;         // the finest cell inside the tile, 0 .. 63
};

// A second hash, independent of pcg_hash (shaders/sampling.glsl): MurmurHash3's 32-bit
// finaliser (Appleby 2011), which Jarzynski and Olano 2020 list among the fast ones.
uint gi1_fmix(uint h) {
  h ^= h >> 16;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  return h ^ (h >> 16);
}

// A cell's size as a power of two: its exponent (in the scene's units, so that every scale
// from millimetres to kilometres has its levels), from the hit's distance along the view:
// `pixel.z` pixels there (distance adaptation, section 2.2.1), never below `pixel.w`.
int gi1_cache_level(GpuGi1Frame f, float view_depth) {
  float size = max(f.pixel.z * gi1_pixel_size(f, view_depth), f.pixel.w);
  return int(floor(log2(max(size, 1e-30))));
}

// The descriptor of a hit at p, found by a ray along `dir` after `ray_length`, seen at
// `view_depth` along the view; `ray_length_bit` adds the ray-length test of section 2.2.2.
Gi1CacheKey gi1_cache_key(GpuGi1Frame f, vec3 p, vec3 dir, float ray_length, float view_depth, bool ray_length_bit) {
  int level = gi1_cache_level(f, view_depth);
  float cell = exp2(float(level)), tile = cell * float(GIQ_GI1_TILE);
  // Tiles far beyond 2^30 of their own size from the origin share the outermost index: such
  // a point has no float precision left to tell its cells apart anyway.
  vec3 tp = clamp(floor(p / tile), vec3(-1073741824.0), vec3(1073741823.0));
  uvec3 c = uvec3(ivec3(tp));
  vec3 e = clamp(floor(p / cell) - tp * float(GIQ_GI1_TILE), vec3(0.0), vec3(float(GIQ_GI1_TILE - 1u)));
  vec3 ad = abs(dir);
  uint axis = ad.x >= ad.y && ad.x >= ad.z ? 0u : (ad.y >= ad.z ? 1u : 2u);
  uint side = dir[axis] < 0.0 ? 1u : 0u;
  uvec2 in_tile = axis == 0u ? uvec2(e.yz) : (axis == 1u ? uvec2(e.xz) : uvec2(e.xy));
  uint short_ray = ray_length_bit && ray_length < tile ? 1u : 0u;
  uint words[6] = uint[6](uint(level), c.x, c.y, c.z, axis * 2u + side, short_ray);
  uint h1 = 0x9e3779b9u, h2 = 0x2545f491u;
  for (int i = 0; i < 6; ++i) {
    h1 = pcg_hash(h1 ^ words[i]);
    h2 = gi1_fmix(h2 ^ words[i] * 0x27d4eb2fu);
  }
  Gi1CacheKey k;
  k.bucket = h1 % f.cache.x;
  k.fingerprint = max(h2, 1u);
  k.cell = in_tile.x + in_tile.y * GIQ_GI1_TILE;
  return k;
}

// The tile holding key k, inserted if it is not there yet, stamped as used in `frame`;
// GIQ_GI1_NONE when its bucket is full. `first_use` is set for exactly one caller per tile
// and frame, so that the tile is listed once for the frame's update.
uint gi1_cache_insert(GpuGi1Frame f, Gi1CacheKey k, uint frame, out bool first_use) {
  first_use = false;
  uint base = k.bucket * f.cache.y, tile = GIQ_GI1_NONE;
  // Look first, then claim: a free slot may sit before the key's own (a tile evicted from
  // the middle of its bucket), and claiming it would store the key twice.
  for (uint i = 0u; i < f.cache.y && tile == GIQ_GI1_NONE; ++i)
    if (cache_hash[base + i] == k.fingerprint) tile = base + i;
  for (uint i = 0u; i < f.cache.y && tile == GIQ_GI1_NONE; ++i) {
    uint prev = atomicCompSwap(cache_hash[base + i], 0u, k.fingerprint);
    if (prev == 0u || prev == k.fingerprint) tile = base + i;
  }
  if (tile != GIQ_GI1_NONE) first_use = atomicExchange(cache_stamp[tile], frame + 1u) != frame + 1u;
  return tile;
}

#endif
