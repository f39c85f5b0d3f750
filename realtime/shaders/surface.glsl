// The local description of a hit, exactly as the reference builds it
// (reference/src/surface.h, make_surface): geometric normal, shading normal (interpolated,
// normal-mapped, turned to the viewer, never below the viewer's horizon) and the material's
// BRDF parameters with their textures applied. Texturing is compiled only for scenes whose
// FeatureSet has textures or normal maps (the reference's kTextures feature bit).
// Needs scene.glsl, brdf.glsl.
#ifndef GIQ_SURFACE_GLSL
#define GIQ_SURFACE_GLSL

#include "scene.glsl"
#include "textures.glsl"
#include "brdf.glsl"

#if defined(GIQ_TEXTURES) || defined(GIQ_NORMAL_MAPS) || defined(GIQ_VERTEX_COLORS)
#define GIQ_SURFACE_TEXTURES 1
#endif

struct HitNormals {
  vec3 ng;     // unit geometric normal on the side the ray came from
  vec3 ns;     // unit shading normal on the same side, with -dir above it
  bool black;  // the back of a one-sided material: absorbs and emits nothing
};

// Barycentrics (of the second and third vertex) of a point p on the plane of triangle
// (a, b, c), clamped to the triangle; for the rasterised G-buffer, whose points come from the
// pixel-centre ray and the triangle's plane.
vec2 plane_barycentrics(vec3 p, vec3 a, vec3 b, vec3 c) {
  vec3 e1 = b - a, e2 = c - a, ep = p - a;
  float d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2), dp1 = dot(ep, e1), dp2 = dot(ep, e2);
  float den = d11 * d22 - d12 * d12;
  float u = den != 0.0 ? clamp((d22 * dp1 - d12 * dp2) / den, 0.0, 1.0) : 0.0;
  float v = den != 0.0 ? clamp((d11 * dp2 - d12 * dp1) / den, 0.0, 1.0) : 0.0;
  return vec2(u, v);
}

// Normals of triangle `tri` at barycentrics (b1, b2), seen along the unit direction `dir`;
// `footprint` selects the normal map's mip level as texture_lod takes it (0: level 0).
HitNormals hit_normals(uint tri, float b1, float b2, vec3 dir, float footprint) {
  GpuTriangle t = scene_triangles[tri];
  GpuMaterial m = scene_materials[t.v.w];
  vec3 p0, p1, p2;
  triangle_vertices(tri, p0, p1, p2);
  vec3 ng = normalize(cross(p1 - p0, p2 - p0));  // glTF front face: counter-clockwise
  bool front = dot(ng, dir) < 0.0;
  HitNormals h;
  h.black = !front && m.params.w == 0.0;
  if (h.black) {
    h.ng = -ng;
    h.ns = -ng;
    return h;
  }
  float b0 = 1.0 - b1 - b2;
  vec3 ns = ng;
  if ((t.extra.z & GIQ_TRIANGLE_HAS_NORMALS) != 0u)
    ns = b0 * scene_vertices[t.v.x].normal.xyz + b1 * scene_vertices[t.v.y].normal.xyz + b2 * scene_vertices[t.v.z].normal.xyz;
#ifdef GIQ_NORMAL_MAPS
  if (m.textures.w >= 0 && (t.extra.z & (reads_uv2(m, GIQ_SLOT_NORMAL) ? GIQ_TRIANGLE_HAS_UVS2 : GIQ_TRIANGLE_HAS_UVS)) != 0u) {
    // Tangent frame: the mesh's tangents (the file's, else MikkTSpace's from the scene library),
    // else (flat shaded, or built in code) dp/du from the triangle's UVs (pbrt-v4, "Triangle
    // Intersection"); the bitangent is sign * cross(n, t) (glTF 2.0, 3.7.2.1), with sign +1 where
    // the UV triangle winds clockwise, since glTF's v runs down the image and the normal map's +Y
    // up it (reference/src/surface.h).
    vec3 tg;
    float sign = 1.0;
    if ((t.extra.z & GIQ_TRIANGLE_HAS_TANGENTS) != 0u) {
      vec4 t4 = b0 * scene_vertex_extra[t.v.x].tangent + b1 * scene_vertex_extra[t.v.y].tangent +
                b2 * scene_vertex_extra[t.v.z].tangent;
      tg = t4.xyz;
      sign = t4.w < 0.0 ? -1.0 : 1.0;
    } else {
      // dp/du in the normal texture's own mapping.
      bool second = reads_uv2(m, GIQ_SLOT_NORMAL);
      vec4 ua = scene_vertex_extra[t.v.x].uv, ub = scene_vertex_extra[t.v.y].uv, uc = scene_vertex_extra[t.v.z].uv;
      vec2 uv0 = second ? ua.zw : ua.xy;
      vec2 d1 = (second ? ub.zw : ub.xy) - uv0, d2 = (second ? uc.zw : uc.xy) - uv0;
      float det = d1.x * d2.y - d1.y * d2.x;
      tg = det != 0.0 ? ((p1 - p0) * d2.y - (p2 - p0) * d1.y) / det : vec3(0.0);
      if (det > 0.0) sign = -1.0;
    }
    tg -= ns * dot(ns, tg);
    float tl = length(tg);
    if (tl > 0.0 && !isinf(tl) && !isnan(tl)) {
      tg /= tl;
      vec3 n0 = normalize(ns);
      vec3 bt = sign * cross(n0, tg);
      float lod = texture_lod(texture_lod(tri, footprint), m, GIQ_SLOT_NORMAL, m.textures.w);
      vec3 n = texture_sample(m.textures.w, triangle_uv(m, GIQ_SLOT_NORMAL, tri, b1, b2), lod).xyz * 2.0 - 1.0;  // [0,1] -> [-1,1]
      n.x *= m.mask.z;
      n.y *= m.mask.z;
      ns = tg * n.x + bt * n.y + n0 * n.z;
    }
  }
#endif
  if (!front) {  // a double-sided material seen from behind
    ng = -ng;
    ns = -ns;
  }
  float nl = length(ns);
  ns = nl > 0.0 && !isinf(nl) && !isnan(nl) ? ns / nl : ng;
  // Interpolated or mapped normals can face away from the viewer while the geometry faces
  // it; shading with them would reflect light from below the surface. The reference falls
  // back to the geometric normal there; so does this.
  if (dot(ns, -dir) <= 1e-4) ns = ng;
  h.ng = ng;
  h.ns = ns;
  return h;
}
HitNormals hit_normals(uint tri, float b1, float b2, vec3 dir) { return hit_normals(tri, b1, b2, dir, 0.0); }

// The BRDF parameters of triangle `tri`'s material at barycentrics (b1, b2), with shading
// normal n: the material's factors times its textures (glTF 2.0 metallic-roughness: G =
// roughness, B = metallic; KHR_materials_specular: specularTexture A, specularColorTexture
// RGB); `footprint` selects mip levels as texture_lod takes it (0: level 0, as every ray).
Surface hit_material(uint tri, float b1, float b2, vec3 n, float footprint) {
  GpuMaterial m = scene_materials[scene_triangles[tri].v.w];
  Surface s = make_surface(m, n);
#ifdef GIQ_SURFACE_TEXTURES
  vec2 uv = triangle_uv(tri, b1, b2, false), uv2 = m.textures2.z != 0 ? triangle_uv(tri, b1, b2, true) : uv;
  TextureLod lod = texture_lod(tri, footprint);
#define GIQ_LOOKUP(slot, index) texture_sample(index, reads_uv2(m, slot) ? uv2 : uv, texture_lod(lod, m, slot, index))
  if (m.textures.x >= 0) s.base_color *= GIQ_LOOKUP(GIQ_SLOT_BASE_COLOR, m.textures.x).rgb;
  if (m.textures.y >= 0) {
    vec4 mr = GIQ_LOOKUP(GIQ_SLOT_METALLIC_ROUGHNESS, m.textures.y);
    s.metallic = clamp(m.params.x * mr.b, 0.0, 1.0);
    float r = clamp(m.params.y * mr.g, 0.0, 1.0);
    s.alpha = max(r * r, 1e-3);
  }
  if (m.textures2.x >= 0) s.specular *= GIQ_LOOKUP(GIQ_SLOT_SPECULAR, m.textures2.x).a;
  if (m.textures2.y >= 0) s.specular_color *= GIQ_LOOKUP(GIQ_SLOT_SPECULAR_COLOR, m.textures2.y).rgb;
#undef GIQ_LOOKUP
  s.base_color *= triangle_color(tri, b1, b2).rgb;  // COLOR_0 (reference make_surface)
#endif
  return s;
}
Surface hit_material(uint tri, float b1, float b2, vec3 n) { return hit_material(tri, b1, b2, n, 0.0); }

#endif
