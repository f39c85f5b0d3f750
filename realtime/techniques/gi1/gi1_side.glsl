// `gi1`'s side cache (Boissé et al. 2022, section 2.1.8): where its per-entry and per-tile words
// lie in the one buffer of them that the includer binds as `side_state[]` (gi1.cpp sizes it):
// each entry's stamp (the last frame + 1 it was used in), each screen tile's listed entry (its
// rank in the LRU order, 0xffffffff none), each entry's claim (the lowest key of the spawn
// slots that write it this frame, 0xffffffff none). The tiles' and the claims' words are
// cleared every frame, the stamps only on the first.
#ifndef GIQ_GI1_SIDE_GLSL
#define GIQ_GI1_SIDE_GLSL

uint gi1_side_stamp(uint e) { return e; }
uint gi1_side_tile(uint t) { return gi1.side.x + t; }
uint gi1_side_claim(uint e) { return gi1.side.x + gi1.size.z * gi1.size.w + e; }

#endif
