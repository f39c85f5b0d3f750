// `gi1`'s probe mask and its mip chain (Boissé et al. 2022, section 2.1.5): level 0 holds,
// per screen tile, the tile itself where it has a probe, else GIQ_GI1_NONE; each coarser
// level keeps the first probe of its 2x2 cells of the level above, so that a search can skip
// a large hole in a few steps (Algorithm 4). The includer declares `probe_mask[]` (all levels
// in a row, the finest first) and reads the frame's constants from `gi1`.
#ifndef GIQ_GI1_MASK_GLSL
#define GIQ_GI1_MASK_GLSL

uvec2 gi1_mask_size(uint level) { return (gi1.size.zw + (1u << level) - 1u) >> level; }

uint gi1_mask_offset(uint level) {
  uint offset = 0u;
  for (uint l = 0u; l < level; ++l) offset += gi1_mask_size(l).x * gi1_mask_size(l).y;
  return offset;
}

// Algorithm 4: the probe nearest to `tile` + `offset` in that direction, looked up at the
// tile's level and, where there is none, at ever coarser levels (the offset in cells of that
// level); GIQ_GI1_NONE when the search leaves the image first. Returns the probe's tile.
uint gi1_find_probe(ivec2 tile, ivec2 offset) {
  uint first = 0u;
  for (uint level = 0u; level < gi1.mask.x; ++level) {
    uvec2 size = gi1_mask_size(level);
    ivec2 pos = tile + offset;
    if (any(lessThan(pos, ivec2(0))) || any(greaterThanEqual(pos, ivec2(size)))) break;
    uint probe = probe_mask[first + uint(pos.x) + uint(pos.y) * size.x];
    if (probe != GIQ_GI1_NONE) return probe;
    first += size.x * size.y;
    tile >>= 1;
  }
  return GIQ_GI1_NONE;
}

#endif
