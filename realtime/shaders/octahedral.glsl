// Octahedral maps of the sphere (Cigolle et al. 2014, "A Survey of Efficient Representations
// for Independent Unit Vectors", JCGT 3(2)), as DDGI stores a probe's irradiance
// and distance moments (Majercik et al. 2019): the square [-1, 1]^2 folds onto
// the octahedron |x| + |y| + |z| = 1; the lower hemisphere (z < 0) lies in the four corners.
// A probe's tile is its n x n interior texels plus a one-texel border that repeats the texels
// across each folded edge, so that bilinear filtering at the tile's edge reads the
// neighbouring directions, not another probe (Majercik et al. 2019).
// tests/realtime/ddgi_test.cpp checks these functions against an independent CPU version.
#ifndef GIQ_OCTAHEDRAL_GLSL
#define GIQ_OCTAHEDRAL_GLSL

vec2 sign_not_zero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }

// Unit direction -> [-1, 1]^2.
vec2 oct_encode(vec3 d) {
  vec2 p = d.xy / (abs(d.x) + abs(d.y) + abs(d.z));
  return d.z < 0.0 ? (1.0 - abs(p.yx)) * sign_not_zero(p) : p;
}

// [-1, 1]^2 -> unit direction.
vec3 oct_decode(vec2 e) {
  vec3 v = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (v.z < 0.0) v.xy = (1.0 - abs(v.yx)) * sign_not_zero(v.xy);
  return normalize(v);
}

// The direction at the centre of interior texel t (0 .. n-1 on each axis) of an n x n map.
vec3 oct_texel_direction(uvec2 t, uint n) { return oct_decode((vec2(t) + 0.5) / float(n) * 2.0 - 1.0); }

// The tile texel (0 .. n+1, interior 1 .. n) a border texel t repeats: across a vertical edge
// the map folds onto itself mirrored in y, across a horizontal edge mirrored in x; a corner
// folds across both (each corner of the square is the direction -z).
uvec2 oct_border_source(uvec2 t, uint n) {
  uvec2 s = t;
  if (s.x == 0u || s.x == n + 1u) s = uvec2(s.x == 0u ? 1u : n, n + 1u - s.y);
  if (s.y == 0u || s.y == n + 1u) s = uvec2(n + 1u - s.x, s.y == 0u ? 1u : n);
  return s;
}

// The first texel of probe p's tile, tiles of (n + 2)^2 texels, `per_row` tiles a row.
uvec2 oct_tile_origin(uint p, uint n, uint per_row) { return uvec2(p % per_row, p / per_row) * (n + 2u); }

// Texture coordinates of direction d in probe p's tile of an atlas of size 1 / inv_size.
vec2 oct_atlas_uv(uint p, vec3 d, uint n, uint per_row, vec2 inv_size) {
  vec2 texel = vec2(oct_tile_origin(p, n, per_row)) + 1.0 + (oct_encode(d) * 0.5 + 0.5) * float(n);
  return texel * inv_size;
}

#endif
