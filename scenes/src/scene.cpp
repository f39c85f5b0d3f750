#include "giq/scenes/scene.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>

#include "giq/base/error.h"
#include "giq/base/suggest.h"
#include "giq/base/hash.h"
#include "giq/scenes/environment.h"
#include "particle_geometry.h"
#include "scene_source.h"

namespace giq::scenes {

Framing frame_bounds(const Bounds& b, double yfov) {
  const glm::dvec3 centre(b.centre());
  const double radius = 0.5 * double(b.diagonal());
  const double distance = 1.05 * radius / std::sin(0.5 * yfov);
  const double elevation = 20.0 * std::numbers::pi / 180.0;
  return {centre + distance * glm::dvec3(0.0, std::sin(elevation), std::cos(elevation)), centre};
}

namespace {

// Rec. ITU-R BT.709 relative luminance of linear RGB.

// Longest edge of triangle t in texels of `tex` through UV set `uvs` (1 without UVs).
float texel_edge(const std::vector<glm::vec2>& uvs, const glm::uvec3& t, const Texture& tex) {
  if (uvs.empty()) return 1.0f;
  const glm::vec2 a = uvs[t.x], b = uvs[t.y], c = uvs[t.z];
  const glm::vec2 size(float(tex.width), float(tex.height));
  const float edge = std::max({glm::length((b - a) * size), glm::length((c - b) * size), glm::length((a - c) * size)});
  return std::isfinite(edge) ? edge : 1.0f;
}

}  // namespace

// Mean emitted radiance over a triangle: emission (factor x emissive texture) times coverage
// (alpha modes: what a ray that finds the point meets, Scene::coverage). The triangle is split
// into k^2 congruent sub-triangles (k even and at least the longest edge in texels of the
// textures involved) and both are evaluated at each sub-triangle's centroid. Exact for
// textures linear over the triangle, and for nearest-filtered texels whose edges fall on the
// subdivision; converging to the area average as k grows otherwise.
glm::vec3 Scene::mean_emitted(const Mesh& m, const glm::uvec3& t, int max_half_k) const {
  const Material& mat = materials[size_t(m.material)];
  const Texture* tex = mat.emissive_texture >= 0 && size_t(mat.emissive_texture) < textures.size() ? &textures[size_t(mat.emissive_texture)] : nullptr;
  const bool covered = mat.alpha_mode != AlphaMode::Opaque;
  if (!tex && !covered) return mat.emissive;
  const std::vector<glm::vec2>& uvs = mat.uv2_slots & kEmissiveSlot ? m.uvs2 : m.uvs;
  float edge = tex ? texel_edge(uvs, t, *tex) : 1.0f;
  if (covered && mat.base_color_texture >= 0 && size_t(mat.base_color_texture) < textures.size())
    edge = std::max(edge, texel_edge(mat.uv2_slots & kBaseColorSlot ? m.uvs2 : m.uvs, t, textures[size_t(mat.base_color_texture)]));
  // Clamped as a float: a huge UV edge would overflow the conversion to int.
  const int k = 2 * int(std::clamp(std::ceil(0.5f * edge), 1.0f, float(max_half_k)));
  const glm::vec2 a = uvs.empty() ? glm::vec2(0.0f) : uvs[t.x], b = uvs.empty() ? a : uvs[t.y], c = uvs.empty() ? a : uvs[t.z];
  glm::dvec3 sum(0.0);
  int count = 0;
  // Sub-triangles of a k-subdivision: "upward" (i, j) and "downward" ones, in barycentric
  // steps of 1/k.
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k - i; ++j) {
      auto at = [&](double u, double v) {
        glm::vec3 e(1.0f);
        if (tex) e = glm::vec3(tex->sample(a + float(u / k) * (b - a) + float(v / k) * (c - a)));
        if (covered) e *= coverage(m, t, float(u / k), float(v / k));
        sum += glm::dvec3(e);
        ++count;
      };
      at(i + 1.0 / 3.0, j + 1.0 / 3.0);
      if (i + j + 1 < k) at(i + 2.0 / 3.0, j + 2.0 / 3.0);
    }
  return mat.emissive * glm::vec3(sum / double(count));
}

void Scene::derive_area_lights() {
  area_lights.clear();
  std::vector<std::vector<uint32_t>> per_mesh(meshes.size());
  for (uint32_t i = 0; i < emissive_triangles.size(); ++i)
    if (emissive_triangles[i].power > 0.0f) per_mesh[emissive_triangles[i].mesh].push_back(i);
  const float offset = 1e-4f * bounds.diagonal();
  for (uint32_t m = 0; m < per_mesh.size(); ++m) {
    const Mesh& mesh = meshes[m];
    // A glowing stage of an emitter's particles is a light in every frame, even one where it
    // has no particle (dark, at the emitter's surface), so that renderers see one set of
    // lights through a sequence.
    const bool stage = mesh.emitter >= 0 && materials[size_t(mesh.material)].is_emissive();
    if (per_mesh[m].empty() && !stage) continue;
    AreaLight l;
    l.mesh = m;
    if (per_mesh[m].empty()) {
      const Emitter& e = emitters[size_t(mesh.emitter)];
      glm::dvec3 centre(0.0);
      for (const glm::dvec3& p : e.surface) centre += p / double(e.surface.size());
      l.centroid = l.representative = glm::vec3(centre);
      // Counted particles (ParticleDetail::Counted): their area and light from the count, the
      // place and extent left to the renderer that places them.
      const Material& mat = materials[size_t(mesh.material)];
      l.two_sided = mat.double_sided;
      l.area = float(double(kParticleTriangles) * mesh.particles * e.face_area());
      l.intensity = mat.emissive * l.area;
      area_lights.push_back(std::move(l));
      continue;
    }
    l.triangles = per_mesh[m];
    l.two_sided = materials[size_t(mesh.material)].double_sided;
    glm::vec3 normal(0.0f);
    for (const uint32_t i : l.triangles) {
      const EmissiveTriangle& e = emissive_triangles[i];
      const glm::uvec3 t = mesh.triangles[e.triangle];
      const glm::vec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
      l.centroid += e.area * (a + b + c) / 3.0f;
      normal += glm::cross(b - a, c - a);
      l.area += e.area;
      l.intensity += e.radiance * e.area;  // a Lambertian emitter: I(n) = L A
    }
    l.centroid /= l.area;
    const float nl = glm::length(normal);
    // Closed (the area vectors cancel) up to their float rounding: |sum| is twice the area
    // of the mean-normal projection, a few ulps of the area for a closed mesh.
    l.flat = nl > 1e-4f * l.area;
    if (l.flat) l.normal = normal / nl;
    l.representative = l.centroid;
    if (!l.two_sided && l.flat) l.representative += l.normal * offset;
    if (!l.flat)
      for (const glm::vec3& v : mesh.positions) l.extent = std::max(l.extent, glm::length(v - l.representative));
    fit_area_shape(mesh, emissive_triangles, l);
    area_lights.push_back(std::move(l));
  }
}

float Scene::coverage(const Mesh& m, const glm::uvec3& t, float b1, float b2) const {
  const Material& mat = materials[size_t(m.material)];
  if (mat.alpha_mode == AlphaMode::Opaque) return 1.0f;
  float alpha = mat.base_color.a;
  const bool second = mat.uv2_slots & kBaseColorSlot;
  if (mat.base_color_texture >= 0 && !(second ? m.uvs2 : m.uvs).empty())
    alpha *= textures[size_t(mat.base_color_texture)].sample(m.uv_at(t, b1, b2, second)).a;
  alpha *= m.color_at(t, b1, b2).a;
  return mat.coverage(alpha);
}

void Scene::derive() {
  features = FeatureSet{};
  emissive_triangles.clear();
  bounds = Bounds{};
  const size_t dropped = stats.degenerate_triangles_dropped;  // counted when posed, kept
  stats = SceneStats{};
  stats.degenerate_triangles_dropped = dropped;

  for (const Light& l : lights) {
    features.directional_lights |= l.type == LightType::Directional;
    features.point_lights |= l.type == LightType::Point;
    features.spot_lights |= l.type == LightType::Spot;
  }
  features.environment = environment != glm::vec3(0.0f) || environment_map >= 0;
  features.environment_map = environment_map >= 0;

  size_t emissive = 0;  // at most: the triangles of emissive meshes (a million particles have eight million)
  for (const Mesh& m : meshes)
    if (m.material >= 0 && size_t(m.material) < materials.size() && materials[size_t(m.material)].is_emissive()) emissive += m.triangles.size();
  emissive_triangles.reserve(emissive);
  bool counted_light = false;  // a stage of counted particles glows (ParticleDetail::Counted)
  for (uint32_t mi = 0; mi < meshes.size(); ++mi) {
    const Mesh& m = meshes[mi];
    const bool counted = m.emitter >= 0 && m.triangles.empty() && m.particles > 0;
    stats.triangles += counted ? size_t(kParticleTriangles) * m.particles : m.triangles.size();
    stats.vertices += counted ? size_t(kParticleVertices) * m.particles : m.positions.size();
    for (const auto& t : m.triangles)
      for (int c = 0; c < 3; ++c)
        if (t[c] < m.positions.size()) bounds.extend(m.positions[t[c]]);
    if ((m.triangles.empty() && !counted) || m.material < 0 || size_t(m.material) >= materials.size()) continue;
    const Material& mat = materials[size_t(m.material)];
    features.specular |= mat.has_specular_lobe();
    features.textures |= mat.has_textures();
    features.normal_maps |= mat.normal_texture >= 0;
    features.vertex_colors |= m.colors.size() == m.positions.size() && !m.colors.empty();
    features.alpha_mask |= mat.alpha_mode != AlphaMode::Opaque;
    features.double_sided |= mat.double_sided;
    features.one_sided |= !mat.double_sided;
    if (m.deformation) {
      features.skinning |= m.deformation->skinned;
      features.morph_targets |= !m.deformation->rest->targets.empty();
    }
    if (!mat.is_emissive()) continue;
    if (counted) {
      // The octahedra's faces, as the placed ones' power below (one material, no texture).
      const double face = emitters[size_t(m.emitter)].face_area();
      stats.total_light_power += double(kParticleTriangles) * m.particles *
                                 float(std::numbers::pi * face * luminance(mat.emissive) * (mat.double_sided ? 2.0 : 1.0));
      counted_light = true;
      continue;
    }
    // k^2 <= 2^24 / triangles samples per triangle, so averaging stays bounded (about 2^24
    // lookups per mesh) however many large triangles a mesh has.
    const int max_half_k = std::clamp(int(std::sqrt(double(1 << 22) / double(m.triangles.size()))), 1, 32);
    for (uint32_t ti = 0; ti < m.triangles.size(); ++ti) {
      const glm::uvec3 t = m.triangles[ti];
      if (t.x >= m.positions.size() || t.y >= m.positions.size() || t.z >= m.positions.size()) continue;
      const glm::vec3 p0 = m.positions[t.x], p1 = m.positions[t.y], p2 = m.positions[t.z];
      EmissiveTriangle e;
      e.mesh = mi;
      e.triangle = ti;
      e.area = 0.5f * glm::length(glm::cross(p1 - p0, p2 - p0));
      e.radiance = mean_emitted(m, t, max_half_k);
      if (!(e.radiance.r > 0.0f || e.radiance.g > 0.0f || e.radiance.b > 0.0f) || !(e.area > 0.0f)) continue;
      // A Lambertian emitter of radiance L and area A emits pi * A * L (per side).
      e.power = float(std::numbers::pi * e.area * luminance(e.radiance) * (mat.double_sided ? 2.0 : 1.0));
      stats.total_light_power += e.power;
      emissive_triangles.push_back(e);
    }
  }
  features.emissive_meshes = !emissive_triangles.empty() || counted_light;

  // Punctual lights, roughly (Light::power), a directional light over the scene's bounding
  // disc.
  const double radius = 0.5 * glm::length(glm::dvec3(bounds.extent()));
  for (const Light& l : lights) stats.total_light_power += l.power(radius);

  derive_area_lights();

  // The sequence moves something when the playing clip has a channel whose keys differ, or an
  // emitter emits, and there is more than one frame to see it.
  if (source_ && sequence.frames > 1 && sequence.animation >= 0 && size_t(sequence.animation) < source_->animations.size()) {
    for (const auto& c : source_->animations[size_t(sequence.animation)].channels)
      features.animation |= c.varies();
  }
  features.particles = !emitters.empty();
  for (const Emitter& e : emitters) features.animation |= sequence.frames > 1 && e.rate > 0.0;
}

double Scene::duration() const {
  if (!source_ || sequence.animation < 0 || size_t(sequence.animation) >= source_->animations.size()) return 0.0;
  return source_->animations[size_t(sequence.animation)].end;
}

Scene Scene::at(double t, ParticleDetail particles) const {
  Scene s;
  at(t, particles, s);
  return s;
}

void Scene::at(double t, ParticleDetail particles, Scene& s) const {
  s = *this;  // copy-assigned: each array keeps its storage where it is large enough
  s.time = t;
  const bool animated = source_ && sequence.animation >= 0;
  if (!animated && emitters.empty()) return;
  if (animated) {
    // This scene's meshes are its pose at its own time: the meshes whose nodes are where they
    // were then are kept.
    const NodePose was = pose_nodes(*source_, sequence.animation, time);
    pose(*source_, pose_nodes(*source_, sequence.animation, t), s, &was);
    s.lights.insert(s.lights.end(), added_lights_.begin(), added_lights_.end());
    s.views.insert(s.views.end(), added_views_.begin(), added_views_.end());
  } else {
    std::erase_if(s.meshes, [](const Mesh& m) { return m.emitter >= 0; });
  }
  add_particle_meshes(s.emitters, t, 1.0 / sequence.fps, particles, s.meshes, path.string());
  s.derive();
}

void Scene::add_light(const Light& light, const std::string& description) {
  added_lights_.push_back(light);
  lights.push_back(light);
  content_hash = Hasher().add(content_hash).add(" + ").add(description).hex();
  derive();
}

void Scene::set_environment(glm::vec3 radiance, const std::string& description) {
  environment = radiance;
  environment_map = -1;
  content_hash = Hasher().add(content_hash).add(" + ").add(description).hex();
  derive();
}

void Scene::set_environment_map(int width, int height, const std::vector<glm::vec3>& radiance, const std::string& description) {
  Texture t;
  t.name = "environment";
  std::vector<glm::vec4> rgba;
  rgba.reserve(radiance.size());
  // The mean radiance over the sphere: texels weighted by their solid angle.
  glm::dvec3 sum(0.0);
  for (int y = 0; y < height; ++y) {
    const double w = std::cos(std::numbers::pi * y / height) - std::cos(std::numbers::pi * (y + 1) / height);
    for (int x = 0; x < width; ++x) {
      const glm::vec3 c = radiance[size_t(y) * size_t(width) + size_t(x)];
      rgba.emplace_back(c, 1.0f);
      sum += w * glm::dvec3(c);
    }
  }
  t.assign(width, height, rgba);
  // Nearest texels, repeating round the horizon, clamped at the poles (scenes/environment.h).
  t.filter = Filter::Nearest;
  t.wrap_s = Wrap::Repeat;
  t.wrap_t = Wrap::ClampToEdge;
  textures.push_back(std::move(t));
  environment_map = int(textures.size() - 1);
  environment = glm::vec3(sum / (2.0 * width));
  content_hash = Hasher().add(content_hash).add(" + ").add(description).hex();
  derive();
}

glm::vec3 Scene::environment_radiance(glm::vec3 dir) const {
  if (environment_map < 0) return environment;
  return glm::vec3(textures[size_t(environment_map)].sample(equirect_uv(dir)));
}

void Scene::add_view(const View& view) {
  for (const View& v : views)
    if (v.name == view.name) throw InputError(path.string(), "views", "the scene has a view named \"" + view.name + "\" already");
  added_views_.push_back(view);
  views.push_back(view);
}

const View& Scene::view(std::string_view name_or_index) const {
  for (const View& v : views)
    if (v.name == name_or_index) return v;
  const bool number = !name_or_index.empty() && name_or_index.size() < 9 &&
                      std::all_of(name_or_index.begin(), name_or_index.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; });
  if (number) {
    const size_t i = std::stoul(std::string(name_or_index));
    if (i < views.size()) return views[i];
  }
  std::string available;
  std::vector<std::string> known;
  for (size_t i = 0; i < views.size(); ++i)
    available += (i ? ", " : "") + std::to_string(i) + " \"" + views[i].name + "\"", known.push_back(views[i].name);
  throw InputError(path.string(), "view", "no view \"" + std::string(name_or_index) + "\"; available: " +
                                              (available.empty() ? "(none)" : available) + did_you_mean(name_or_index, known));
}

}  // namespace giq::scenes
