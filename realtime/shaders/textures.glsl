// Texture lookups, texture coordinates and the alpha-mask test, with the arithmetic of the
// scene library (scenes/src/texture.cpp, Texture::sample) and of the reference
// (reference/src/surface.h, reference/src/embree_scene.cpp). Textures are 8-bit (or float)
// RGBA texels read through buffer device addresses (GpuTexture::texels, SceneGpu) and decoded
// and filtered here by hand: the same floats as the reference (one decode table, scene.glsl's
// GIQ_BINDING_DECODE), the same wrap modes and the same bilinear weights (the same bits for
// power-of-two sizes), on every Vulkan device without samplers or descriptor indexing.
// Level 0 is what every ray reads; the mip levels (texture_mips.comp) serve the G-buffer's
// primary hits only, one pixel's footprint each (texture_lod below, docs/realtime.md).
// Needs scene.glsl.
#ifndef GIQ_TEXTURES_GLSL
#define GIQ_TEXTURES_GLSL

#include "scene.glsl"
#include "sampling.glsl"

#if defined(GIQ_TEXTURES) || defined(GIQ_NORMAL_MAPS) || defined(GIQ_ALPHA_MASK) || defined(GIQ_VERTEX_COLORS) || defined(GIQ_ENVIRONMENT_MAP)

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer TexelWords { uint words[]; };

// An integer texel coordinate i (held in a float) mapped onto [0, n) by a glTF wrap mode
// (glTF 2.0, 5.26 "Sampler": OpenGL REPEAT, CLAMP_TO_EDGE, MIRRORED_REPEAT).
int texture_wrap(float i, float n, uint mode) {
  float w;
  if (mode == GIQ_WRAP_REPEAT) {
    w = i - n * floor(i / n);
  } else if (mode == GIQ_WRAP_CLAMP) {
    w = clamp(i, 0.0, n - 1.0);
  } else {
    float m = i - 2.0 * n * floor(i / (2.0 * n));
    w = m < n ? m : 2.0 * n - 1.0 - m;
  }
  // Rounding in the divisions can land exactly on n for huge |i|.
  return clamp(int(w), 0, int(n) - 1);
}

// Mip level `level` of t: max(1, size >> level) texels a side (GL's rounding down), stored
// after the levels above it; GpuTexture::info.x levels in all (1: level 0 only).
uvec2 mip_size(GpuTexture t, uint level) { return max(uvec2(1u), uvec2(t.info.y, t.info.z) >> level); }
uint mip_first_texel(GpuTexture t, uint level) {
  uint first = 0u;
  for (uint l = 0u; l < level; ++l) {
    uvec2 s = mip_size(t, l);
    first += s.x * s.y;
  }
  return first;
}

// Texel i of t's words (level 0 row-major, then the mip levels), decoded as
// scenes::Texture::texel does: 8-bit channels through the decode table (the same floats as
// the reference's), float texels as stored.
vec4 texel_word(GpuTexture t, uint i) {
  uint format = (t.info.w >> 5) & 3u;
  TexelWords texels = TexelWords(t.texels.xy);
  if (format == GIQ_TEXELS_RGBA32F) {
    uint w = 4u * i;
    return uintBitsToFloat(uvec4(texels.words[w], texels.words[w + 1u], texels.words[w + 2u], texels.words[w + 3u]));
  }
  uint p = texels.words[i], colour = format == GIQ_TEXELS_RGBA8_SRGB ? GIQ_DECODE_SRGB : 0u;
  return vec4(scene_decode[colour + (p & 255u)], scene_decode[colour + ((p >> 8) & 255u)],
              scene_decode[colour + ((p >> 16) & 255u)], scene_decode[p >> 24]);
}
// Texel (x, y) of the level that starts at texel `first` and is `width` texels wide.
vec4 texel_at(GpuTexture t, uint first, uint width, int x, int y) { return texel_word(t, first + uint(y) * width + uint(x)); }

// Level `level` of t at (u, v): nearest or bilinear between the four nearest texel centres,
// which sit at (i + 0.5) / size; first texel row at v = 0 (glTF's top-left origin).
vec4 texture_level(GpuTexture t, uint level, float u, float v) {
  uvec2 size = mip_size(t, level);
  uint first = level == 0u ? 0u : mip_first_texel(t, level);
  float w = float(size.x), h = float(size.y);
  uint wrap_s = t.info.w & 3u, wrap_t = (t.info.w >> 2) & 3u;
  if (((t.info.w >> 4) & 1u) == GIQ_FILTER_NEAREST)
    return texel_at(t, first, size.x, texture_wrap(floor(u * w), w, wrap_s), texture_wrap(floor(v * h), h, wrap_t));
  // Texture::sample forms x = u * width - 0.5 in double, x0 = floor(x) and the weight
  // fx = float(x - x0), rounded once. Here p = u * width is exact in float for power-of-two
  // sizes (rounded once otherwise, which moves the weights by at most 2^-24 |u| width);
  // x0 + 0.5 is exact, so p - (x0 + 0.5) is x - x0 rounded once, as the reference rounds it.
  // x0 from the float p - 0.5 can be one too large where that rounds up onto an integer; the
  // weight then comes out negative, and one step down fixes it. `precise` keeps every
  // product and sum here and below separately rounded (no fused multiply-add), as in C++.
  precise float px = u * w;
  precise float py = v * h;
  float x0 = floor(px - 0.5), y0 = floor(py - 0.5);
  precise float fx = px - (x0 + 0.5);
  precise float fy = py - (y0 + 0.5);
  if (fx < 0.0) {
    x0 -= 1.0;
    fx = px - (x0 + 0.5);
  }
  if (fy < 0.0) {
    y0 -= 1.0;
    fy = py - (y0 + 0.5);
  }
  int xa = texture_wrap(x0, w, wrap_s), xb = texture_wrap(x0 + 1.0, w, wrap_s);
  int ya = texture_wrap(y0, h, wrap_t), yb = texture_wrap(y0 + 1.0, h, wrap_t);
  precise vec4 top = texel_at(t, first, size.x, xa, ya) * (1.0 - fx) + texel_at(t, first, size.x, xb, ya) * fx;
  precise vec4 bottom = texel_at(t, first, size.x, xa, yb) * (1.0 - fx) + texel_at(t, first, size.x, xb, yb) * fx;
  precise vec4 r = top * (1.0 - fy) + bottom * fy;
  return r;
}

// Texture `index` at uv and mip level `lod` (texture_lod): level 0 alone, the reference's
// lookup, where lod is 0 or less (or NaN) or the texture has no mip levels; else linear
// between the two nearest levels (trilinear filtering), the last level beyond it.
vec4 texture_sample(int index, vec2 uv, float lod) {
  GpuTexture t = scene_textures[index];
  if (t.info.y == 0u || t.info.z == 0u) return vec4(0.0);
  // Beyond |uv| = 1e6 a float uv cannot address a texel anyway (as Texture::sample).
  float u = isnan(uv.x) || isinf(uv.x) ? 0.0 : clamp(uv.x, -1e6, 1e6);
  float v = isnan(uv.y) || isinf(uv.y) ? 0.0 : clamp(uv.y, -1e6, 1e6);
  uint levels = max(t.info.x, 1u);
  if (!(lod > 0.0) || levels == 1u) return texture_level(t, 0u, u, v);
  float l = min(lod, float(levels - 1u));
  uint l0 = uint(l);
  float f = l - float(l0);
  vec4 a = texture_level(t, l0, u, v);
  return f > 0.0 ? mix(a, texture_level(t, l0 + 1u, u, v), f) : a;
}
vec4 texture_sample(int index, vec2 uv) { return texture_sample(index, uv, 0.0); }

// Whether the texture in `slot` (GIQ_SLOT_*) of material m reads the second mapping.
bool reads_uv2(GpuMaterial m, uint slot) { return (uint(m.textures2.z) & slot) != 0u; }

// The first or second texture-coordinate mapping at barycentrics (b1, b2) of triangle `tri`;
// 0 when its mesh has none, as scenes::Mesh::uv_at.
vec2 triangle_uv(uint tri, float b1, float b2, bool second) {
  uvec4 v = scene_triangles[tri].v;
  if ((scene_triangles[tri].extra.z & (second ? GIQ_TRIANGLE_HAS_UVS2 : GIQ_TRIANGLE_HAS_UVS)) == 0u) return vec2(0.0);
  vec4 a = scene_vertex_extra[v.x].uv, b = scene_vertex_extra[v.y].uv, c = scene_vertex_extra[v.z].uv;
  return second ? (1.0 - b1 - b2) * a.zw + b1 * b.zw + b2 * c.zw : (1.0 - b1 - b2) * a.xy + b1 * b.xy + b2 * c.xy;
}
// The coordinates the texture in `slot` of the triangle's material m reads.
vec2 triangle_uv(GpuMaterial m, uint slot, uint tri, float b1, float b2) { return triangle_uv(tri, b1, b2, reads_uv2(m, slot)); }

// Mip selection for a hit that one pixel sees, `footprint` apart from its neighbours' hits
// (pixel_footprint, camera.glsl): lod = log2(footprint x texels per unit length), with the
// texel density constant over the triangle, sqrt(texels x uv area / surface area)
// (Akenine-Moeller et al. 2019, "Texture Level of Detail Strategies for Real-Time Ray
// Tracing", Ray Tracing Gems ch. 20: its ray-cone lod, with the cone's width at the hit
// replaced by the exact footprint). TextureLod holds the per-triangle part for each mapping;
// footprint 0 (every ray but the G-buffer's) gives -1e30: level 0.
struct TextureLod {
  vec2 base;  // log2(footprint) + 0.5 log2(uv area / surface area), mappings 1 and 2
};
TextureLod texture_lod(uint tri, float footprint) {
  TextureLod l;
  l.base = vec2(-1e30);
  if (!(footprint > 0.0)) return l;
  uvec4 v = scene_triangles[tri].v;
  vec3 p0, p1, p2;
  triangle_vertices(tri, p0, p1, p2);
  float surface = length(cross(p1 - p0, p2 - p0));
  vec4 a = scene_vertex_extra[v.x].uv, b = scene_vertex_extra[v.y].uv, c = scene_vertex_extra[v.z].uv;
  vec4 e1 = b - a, e2 = c - a;
  vec2 uv_area = abs(vec2(e1.x * e2.y - e1.y * e2.x, e1.z * e2.w - e1.w * e2.z));
  // Zero uv area: -inf, level 0; zero surface area (never seen): +inf, the last level.
  l.base = log2(footprint) + 0.5 * (log2(uv_area) - log2(surface));
  return l;
}
float texture_lod(TextureLod l, GpuMaterial m, uint slot, int index) {
  GpuTexture t = scene_textures[index];
  return (reads_uv2(m, slot) ? l.base.y : l.base.x) + 0.5 * log2(float(t.info.y) * float(t.info.z));
}

// COLOR_0 at barycentrics (b1, b2) of triangle `tri`; white when its mesh has none, as
// scenes::Mesh::color_at.
vec4 triangle_color(uint tri, float b1, float b2) {
  uvec4 v = scene_triangles[tri].v;
  if ((scene_triangles[tri].extra.z & GIQ_TRIANGLE_HAS_COLORS) == 0u) return vec4(1.0);
  return (1.0 - b1 - b2) * scene_vertex_extra[v.x].color + b1 * scene_vertex_extra[v.y].color + b2 * scene_vertex_extra[v.z].color;
}

#endif

#ifdef GIQ_ALPHA_MASK
// glTF 2.0, 3.9.4 "Alpha Coverage", as scenes::Scene::coverage: alpha is baseColorFactor.a
// times the base colour texture's alpha at uv (its mapping's coordinates, when the mesh has
// them) times
// COLOR_0's alpha (`vertex_alpha`); a MASK surface is there (1) or not (0) by alphaCutoff, a
// BLEND surface is there with probability alpha (stochastic transparency).
float alpha_coverage(GpuMaterial m, uint tri, vec2 uv, float vertex_alpha) {
  if (m.mask.x == 0.0) return 1.0;
  float alpha = m.base_color.a;
  uint has = reads_uv2(m, GIQ_SLOT_BASE_COLOR) ? GIQ_TRIANGLE_HAS_UVS2 : GIQ_TRIANGLE_HAS_UVS;
  if (m.textures.x >= 0 && (scene_triangles[tri].extra.z & has) != 0u) alpha *= texture_sample(m.textures.x, uv).a;
  alpha *= vertex_alpha;
  if (m.mask.x == 1.0) return alpha < m.mask.y ? 0.0 : 1.0;
  return clamp(alpha, 0.0, 1.0);
}

float alpha_coverage(uint tri, float b1, float b2) {
  GpuMaterial m = scene_materials[scene_triangles[tri].v.w];
  if (m.mask.x == 0.0) return 1.0;
  return alpha_coverage(m, tri, triangle_uv(m, GIQ_SLOT_BASE_COLOR, tri, b1, b2), triangle_color(tri, b1, b2).a);
}

// Whether a point is absent, given xi uniform in [0, 1) from the caller: a hash of the ray
// for ray casts (alpha_ray_number), of the pixel for rasterised passes (alpha_pixel_number,
// an ordered screen-door dither of BLEND). MASK ignores xi.
bool alpha_cut(uint tri, float b1, float b2, float xi) { return xi >= alpha_coverage(tri, b1, b2); }

float alpha_hash_number(uint h) {
  h = pcg_hash(h);
  return float(h >> 8u) * (1.0 / 16777216.0);
}
float alpha_ray_number(vec3 org, vec3 dir, uint tri) {
  uvec3 o = floatBitsToUint(org), d = floatBitsToUint(dir);
  return alpha_hash_number(o.x ^ pcg_hash(o.y ^ pcg_hash(o.z ^ pcg_hash(d.x ^ pcg_hash(d.y ^ pcg_hash(d.z ^ pcg_hash(tri)))))));
}
float alpha_pixel_number(vec2 frag, uint tri) {
  uvec2 p = uvec2(frag);
  return alpha_hash_number(p.x ^ pcg_hash(p.y ^ pcg_hash(tri)));
}
#endif

// Radiance emitted at barycentrics (b1, b2) of triangle `tri` (front side; the caller
// decides about the back): emissive factor times the emissive texture (reference
// emitted_radiance).
// `footprint` as texture_lod takes it (0: level 0).
vec3 emission_at(GpuMaterial m, uint tri, float b1, float b2, float footprint) {
  vec3 e = m.emissive.rgb;
#if defined(GIQ_TEXTURES) || defined(GIQ_NORMAL_MAPS)
  if (m.textures.z >= 0)
    e *= texture_sample(m.textures.z, triangle_uv(m, GIQ_SLOT_EMISSIVE, tri, b1, b2),
                        texture_lod(texture_lod(tri, footprint), m, GIQ_SLOT_EMISSIVE, m.textures.z)).rgb;
#endif
  return e;
}
vec3 emission_at(GpuMaterial m, uint tri, float b1, float b2) { return emission_at(m, tri, b1, b2, 0.0); }

#endif
