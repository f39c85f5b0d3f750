#pragma once
// The local description of a ray's hit: position, geometric and shading normals, texture
// coordinates and the material's parameters there, with textures and normal maps applied
// when the integrator's feature mask includes them.

#include <glm/glm.hpp>

#include "bsdf_params.h"
#include "feature_mask.h"
#include "giq/reference/bsdf.h"
#include "giq/reference/ray_offset.h"
#include "render_context.h"

namespace giq::reference {

struct Surface {
  glm::vec3 p{0.0f};   // on the triangle, from barycentrics (more accurate than o + t d)
  glm::vec3 ng{0.0f};  // unit geometric normal on the side the ray came from
  glm::vec3 ns{0.0f};  // unit shading normal on the same side, with wo above it
  glm::vec3 emission{0.0f};
  float area = 0.0f;    // of the hit triangle (for the light pdf of MIS)
  float offset = 0.0f;  // ray_offset of the hit triangle
  float cos_ray = 0.0f; // |cos| between the ray and the geometric normal
  const scenes::Material* material = nullptr;
  BsdfParams bsdf;
  bool black = false;   // the back of a one-sided material: absorbs and emits nothing
};

template <unsigned F>
Surface make_surface(const RenderContext& ctx, const Hit& hit, glm::vec3 dir) {
  Surface s;
  const scenes::Mesh& mesh = ctx.scene.meshes[hit.mesh];
  const glm::uvec3 tri = mesh.triangles[hit.triangle];
  const std::vector<glm::vec3>& pos = ctx.bvh.positions()[hit.mesh];
  const float b1 = hit.b1, b2 = hit.b2, b0 = 1.0f - b1 - b2;
  const glm::vec3 p0 = pos[tri.x], p1 = pos[tri.y], p2 = pos[tri.z];
  s.p = b0 * p0 + b1 * p1 + b2 * p2;
  const TriangleShape& shape = ctx.bvh.shapes()[hit.mesh][hit.triangle];
  s.offset = shape.offset;
  s.area = shape.area;
  glm::vec3 ng = shape.normal;
  const float cos_ray = glm::dot(ng, dir);
  s.cos_ray = std::abs(cos_ray);
  const bool front = cos_ray < 0.0f;
  const scenes::Material& m = ctx.scene.materials[size_t(mesh.material)];
  s.material = &m;
  if (!front && !m.double_sided) {
    s.black = true;
    s.ng = -ng;
    s.ns = -ng;
    return s;
  }

  glm::vec3 ns = mesh.normals.empty() ? ng : b0 * mesh.normals[tri.x] + b1 * mesh.normals[tri.y] + b2 * mesh.normals[tri.z];
  glm::vec3 base = glm::vec3(m.base_color);
  float metallic = m.metallic, roughness = m.roughness, specular = m.specular;
  glm::vec3 specular_color = m.specular_color;
  glm::vec2 uv(0.0f);
  if constexpr (has(F, kTextures)) {
    // The material's first texture-coordinate mapping, and its second where a slot reads it.
    uv = mesh.uv_at(tri, b1, b2);
    const glm::vec2 uv2 = m.uv2_slots ? mesh.uv_at(tri, b1, b2, true) : uv;
    // Every lookup is located before any is fetched, so that their waits on memory overlap
    // (Texture::locate).
    using Footprint = scenes::Texture::Footprint;
    const auto locate = [&](int i, scenes::TextureSlot slot) {
      return i >= 0 ? ctx.scene.textures[size_t(i)].locate(m.uv2_slots & slot ? uv2 : uv) : Footprint{};
    };
    const Footprint f_base = locate(m.base_color_texture, scenes::kBaseColorSlot);
    const Footprint f_mr = locate(m.metallic_roughness_texture, scenes::kMetallicRoughnessSlot);
    const Footprint f_normal = locate(m.normal_texture, scenes::kNormalSlot);
    const Footprint f_spec = locate(m.specular_texture, scenes::kSpecularSlot);
    const Footprint f_spec_color = locate(m.specular_color_texture, scenes::kSpecularColorSlot);
    const auto tex = [&](int i, const Footprint& f) { return ctx.scene.textures[size_t(i)].fetch(f); };
    if (m.base_color_texture >= 0) base *= glm::vec3(tex(m.base_color_texture, f_base));
    base *= glm::vec3(mesh.color_at(tri, b1, b2));
    if (m.metallic_roughness_texture >= 0) {
      const glm::vec4 t = tex(m.metallic_roughness_texture, f_mr);  // glTF: G = roughness, B = metallic
      roughness *= t.g, metallic *= t.b;
    }
    if (m.specular_texture >= 0) specular *= tex(m.specular_texture, f_spec).a;
    if (m.specular_color_texture >= 0) specular_color *= glm::vec3(tex(m.specular_color_texture, f_spec_color));
    const std::vector<glm::vec2>& normal_uvs = m.uv2_slots & scenes::kNormalSlot ? mesh.uvs2 : mesh.uvs;
    if (m.normal_texture >= 0 && !normal_uvs.empty()) {
      // Tangent frame: the mesh's tangents (the file's, else MikkTSpace's from the scene library),
      // else (flat shaded, or built in code) dp/du from the triangle's UVs (pbrt-v4, "Triangle
      // Intersection": partial derivatives from the UV parameterisation). glTF's v runs down the
      // image and the normal map's +Y up it, so the bitangent sign is +1 where the UV triangle
      // winds clockwise (det < 0), as scenes/src/tangent_space.h has it.
      glm::vec3 t;
      float sign = 1.0f;
      if (!mesh.tangents.empty()) {
        const glm::vec4 t4 = b0 * mesh.tangents[tri.x] + b1 * mesh.tangents[tri.y] + b2 * mesh.tangents[tri.z];
        t = glm::vec3(t4), sign = t4.w < 0.0f ? -1.0f : 1.0f;
      } else {
        const glm::vec2 d1 = normal_uvs[tri.y] - normal_uvs[tri.x], d2 = normal_uvs[tri.z] - normal_uvs[tri.x];
        const float det = d1.x * d2.y - d1.y * d2.x;
        t = det != 0.0f ? ((p1 - p0) * d2.y - (p2 - p0) * d1.y) / det : glm::vec3(0.0f);
        if (det > 0.0f) sign = -1.0f;
      }
      t -= ns * glm::dot(ns, t);
      const float tl = glm::length(t);
      if (tl > 0.0f && std::isfinite(tl)) {
        t /= tl;
        const glm::vec3 b = sign * glm::cross(glm::normalize(ns), t);
        glm::vec3 n = glm::vec3(tex(m.normal_texture, f_normal)) * 2.0f - 1.0f;  // glTF: [0,1] -> [-1,1]
        n.x *= m.normal_scale, n.y *= m.normal_scale;
        ns = t * n.x + b * n.y + glm::normalize(ns) * n.z;
      }
    }
  }
  if (!front) ng = -ng, ns = -ns;  // a double-sided material seen from behind
  const float nl = glm::length(ns);
  ns = nl > 0.0f && std::isfinite(nl) ? ns / nl : ng;
  // Interpolated or mapped normals can face away from the viewer while the geometry faces it;
  // shading with them would reflect light from below the surface. Fall back to the geometric
  // normal there (a pragmatic choice; cf. Veach 1996, "Non-symmetric Scattering in Light
  // Transport Algorithms", on shading normals).
  if (glm::dot(ns, -dir) <= 1e-4f) ns = ng;
  s.ng = ng;
  s.ns = ns;

  if constexpr (has(F, kTextures))
    s.bsdf = bsdf_params<F>(m, base, metallic, roughness, specular, specular_color);
  else
    s.bsdf = ctx.material_bsdf[size_t(mesh.material)];  // the same values, computed once
  if constexpr (has(F, kEmissive)) {
    if (m.is_emissive()) s.emission = emitted_radiance<F>(ctx.scene, m, m.uv2_slots & scenes::kEmissiveSlot ? mesh.uv_at(tri, b1, b2, true) : uv);
  }
  return s;
}

}  // namespace giq::reference
