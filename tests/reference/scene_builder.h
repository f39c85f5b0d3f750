#pragma once
// Scenes built in code for the reference tests: quads, boxes and a Cornell-like box, with
// materials whose response is known in closed form.

#include <glm/glm.hpp>

#include <cmath>
#include <vector>

#include "giq/reference/film.h"
#include "giq/scenes/scene.h"

namespace giq::reference::test {

// A Lambertian material: no GGX lobe (metallic 0, KHR_materials_specular factor 0).
inline scenes::Material diffuse(glm::vec3 albedo, glm::vec3 emission = glm::vec3(0.0f), bool double_sided = false) {
  scenes::Material m;
  m.base_color = glm::vec4(albedo, 1.0f);
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  m.specular = 0.0f;
  m.emissive = emission;
  m.double_sided = double_sided;
  return m;
}

inline int add_material(scenes::Scene& s, const scenes::Material& m) {
  s.materials.push_back(m);
  return int(s.materials.size() - 1);
}

// A quad a-b-c-d, counter-clockwise seen from its front (glTF's front face), as one mesh.
inline void add_quad(scenes::Scene& s, int material, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d,
                     uint32_t object_id = 1) {
  scenes::Mesh m;
  m.name = "quad" + std::to_string(s.meshes.size());
  m.node = int(s.meshes.size());
  m.object_id = object_id;
  m.material = material;
  m.positions = {a, b, c, d};
  const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
  m.normals = {n, n, n, n};
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  s.meshes.push_back(std::move(m));
}

// The six faces of the axis-aligned box [lo, hi], fronts facing inwards (or outwards).
inline void add_box(scenes::Scene& s, int material, glm::vec3 lo, glm::vec3 hi, bool inward, uint32_t object_id = 1) {
  const glm::vec3 p[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                          {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  // Outward counter-clockwise faces; reversed for inward ones.
  const int f[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 4, 7, 3}, {1, 2, 6, 5}};
  for (const auto& q : f) {
    if (inward)
      add_quad(s, material, p[q[3]], p[q[2]], p[q[1]], p[q[0]], object_id);
    else
      add_quad(s, material, p[q[0]], p[q[1]], p[q[2]], p[q[3]], object_id);
  }
}

// A Cornell-like box: a 2 x 2 x 2 room (y up) open towards +z, red left wall, green right wall,
// white floor, ceiling and back, a square area light under the ceiling and a white block;
// camera at z = 3.4 looking at the room. `scale` and `offset` pose it; `light` scales the
// emitted radiance.
inline scenes::Scene cornell(float scale = 1.0f, glm::vec3 offset = glm::vec3(0.0f), float light = 1.0f) {
  scenes::Scene s;
  const auto P = [&](float x, float y, float z) { return glm::vec3(x, y, z) * scale + offset; };
  const int white = add_material(s, diffuse({0.73f, 0.73f, 0.73f}));
  const int red = add_material(s, diffuse({0.63f, 0.065f, 0.05f}));
  const int green = add_material(s, diffuse({0.14f, 0.45f, 0.09f}));
  const int lamp = add_material(s, diffuse({0.78f, 0.78f, 0.78f}, glm::vec3(17.0f, 12.0f, 4.0f) * light));
  add_quad(s, white, P(-1, -1, 1), P(1, -1, 1), P(1, -1, -1), P(-1, -1, -1), 2);   // floor
  add_quad(s, white, P(-1, 1, -1), P(1, 1, -1), P(1, 1, 1), P(-1, 1, 1), 3);       // ceiling
  add_quad(s, white, P(-1, -1, -1), P(1, -1, -1), P(1, 1, -1), P(-1, 1, -1), 4);   // back
  add_quad(s, red, P(-1, -1, 1), P(-1, -1, -1), P(-1, 1, -1), P(-1, 1, 1), 5);     // left
  add_quad(s, green, P(1, -1, -1), P(1, -1, 1), P(1, 1, 1), P(1, 1, -1), 6);       // right
  add_quad(s, lamp, P(-0.25f, 0.99f, -0.25f), P(0.25f, 0.99f, -0.25f), P(0.25f, 0.99f, 0.25f), P(-0.25f, 0.99f, 0.25f), 7);
  add_box(s, white, glm::vec3(-0.6f, -1.0f, -0.5f) * scale + offset, glm::vec3(-0.05f, 0.2f, 0.1f) * scale + offset, false, 8);
  scenes::View v;
  v.name = "front";
  v.camera = scenes::Camera::look_at(P(0, 0, 3.4f), P(0, 0, 0), {0, 1, 0}, 0.7f);
  s.views.push_back(v);
  s.derive();
  return s;
}

// A glossy and a diffuse block on a floor, under a large area light and a dim environment,
// so every estimator has finite variance and MIS has both strategies to weigh.
inline scenes::Scene glossy_scene() {
  scenes::Scene s;
  const int floor = test::add_material(s, test::diffuse({0.6f, 0.6f, 0.5f}));
  scenes::Material metal;
  metal.base_color = {0.9f, 0.7f, 0.4f, 1.0f};
  metal.metallic = 1.0f;
  metal.roughness = 0.45f;
  const int gloss = test::add_material(s, metal);
  scenes::Material plastic = test::diffuse({0.2f, 0.4f, 0.8f});
  plastic.specular = 1.0f;
  plastic.roughness = 0.3f;
  const int plast = test::add_material(s, plastic);
  const int lamp = test::add_material(s, test::diffuse(glm::vec3(0.0f), glm::vec3(2.0f, 1.8f, 1.5f), true));
  test::add_quad(s, floor, {-3, 0, 3}, {3, 0, 3}, {3, 0, -3}, {-3, 0, -3}, 1);
  test::add_box(s, gloss, {-1.2f, 0.0f, -0.6f}, {-0.2f, 1.0f, 0.4f}, false, 2);
  test::add_box(s, plast, {0.3f, 0.0f, -0.3f}, {1.1f, 0.6f, 0.5f}, false, 3);
  test::add_quad(s, lamp, {-1.5f, 2.5f, 1.5f}, {1.5f, 2.5f, 1.5f}, {1.5f, 2.5f, -1.5f}, {-1.5f, 2.5f, -1.5f}, 4);
  s.environment = glm::vec3(0.15f, 0.2f, 0.3f);
  s.derive();
  return s;
}

// The view of glossy_scene() the tests render: both blocks, the floor and the light's glow.
inline scenes::Camera glossy_scene_camera() {
  return scenes::Camera::look_at({0.5f, 2.2f, 3.5f}, {0.0f, 0.4f, 0.0f}, {0, 1, 0}, 0.9f);
}

// Mean and variance of the mean of the luminance of the beauty over a block of pixels
// (pixels are independent, so their variances add).
struct BlockStat {
  double mean = 0.0;
  double variance = 0.0;
};
inline BlockStat block_luminance(const Film& f, int x0, int y0, int w, int h) {
  const double k[3] = {0.2126, 0.7152, 0.0722};
  BlockStat b;
  const double n = double(w) * double(h);
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x) {
      const PixelAccumulator& p = f.pixels[size_t(y) * size_t(f.width) + size_t(x)];
      double sigma = 0.0;  // bound on the luminance's standard error (channels fully correlated)
      for (int c = 0; c < 3; ++c) {
        b.mean += k[c] * p.mean[c] / n;
        sigma += k[c] * std::sqrt(p.variance_of_mean(c));
      }
      b.variance += sigma * sigma / (n * n);
    }
  return b;
}

}  // namespace giq::reference::test
