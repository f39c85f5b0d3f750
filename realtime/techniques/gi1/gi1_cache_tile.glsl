// A tile of `gi1`'s world cache (Boissé et al. 2022, section 2.2.3, Figure 13): 8x8 cells and
// their mip levels 4x4, 2x2 and 1x1, 85 cells in a row, the finest first. Needs gi1_shared.h.
#ifndef GIQ_GI1_CACHE_TILE_GLSL
#define GIQ_GI1_CACHE_TILE_GLSL

// The first cell of mip level `level` (0 .. 3).
uint gi1_tile_level_offset(uint level) { return level == 0u ? 0u : (level == 1u ? 64u : (level == 2u ? 80u : 84u)); }

// Finest cell `cell` (0 .. 63) at mip level `level`, as an index into the tile's 85 cells.
uint gi1_tile_cell(uint cell, uint level) {
  uint side = GIQ_GI1_TILE >> level;
  uvec2 xy = uvec2(cell % GIQ_GI1_TILE, cell / GIQ_GI1_TILE) >> level;
  return gi1_tile_level_offset(level) + xy.x + xy.y * side;
}

#endif
