#include "scene_builders.h"

#include <cmath>
#include <glm/geometric.hpp>

namespace giq::test {

void add_quad(scenes::Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, int material) {
  scenes::Mesh m;
  m.name = "quad" + std::to_string(s.meshes.size());
  m.node = int(s.meshes.size());
  m.object_id = uint32_t(s.meshes.size() + 1);
  m.material = material;
  const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
  m.positions = {a, b, c, d};
  m.normals = {n, n, n, n};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  s.meshes.push_back(std::move(m));
}

int add_material(scenes::Scene& s, glm::vec3 albedo, glm::vec3 emissive) {
  scenes::Material m;
  m.name = "material" + std::to_string(s.materials.size());
  m.base_color = glm::vec4(albedo, 1.0f);
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  m.specular = 0.0f;  // pure Lambert: KHR_materials_specular factor 0
  m.emissive = emissive;
  s.materials.push_back(m);
  return int(s.materials.size() - 1);
}

int add_texture(scenes::Scene& s, int w, int h, const std::function<glm::vec4(int, int)>& texel, scenes::Filter filter,
                scenes::Wrap wrap) {
  scenes::Texture t;
  t.name = "texture" + std::to_string(s.textures.size());
  std::vector<glm::vec4> texels;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) texels.push_back(texel(x, y));
  t.assign(w, h, texels);
  t.filter = filter;
  t.wrap_s = t.wrap_t = wrap;
  s.textures.push_back(std::move(t));
  return int(s.textures.size() - 1);
}

void add_textured_quad(scenes::Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, int material, float uv_scale) {
  add_quad(s, a, b, c, d, material);
  const float k = uv_scale;
  s.meshes.back().uvs = {{0.0f, 0.0f}, {k, 0.0f}, {k, k}, {0.0f, k}};
}

namespace {
// An axis-aligned block [lo, hi] with outward faces.
void add_block(scenes::Scene& s, glm::vec3 lo, glm::vec3 hi, int mat) {
  const glm::vec3 p[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                          {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  add_quad(s, p[4], p[5], p[6], p[7], mat);  // +z
  add_quad(s, p[1], p[0], p[3], p[2], mat);  // -z
  add_quad(s, p[5], p[1], p[2], p[6], mat);  // +x
  add_quad(s, p[0], p[4], p[7], p[3], mat);  // -x
  add_quad(s, p[7], p[6], p[2], p[3], mat);  // +y
  add_quad(s, p[0], p[1], p[5], p[4], mat);  // -y
}
}  // namespace

scenes::Scene cornell_box(glm::vec3 light_radiance) {
  scenes::Scene s;
  const int white = add_material(s, glm::vec3(0.73f));
  const int red = add_material(s, glm::vec3(0.65f, 0.05f, 0.05f));
  const int green = add_material(s, glm::vec3(0.12f, 0.45f, 0.15f));
  const int light = add_material(s, glm::vec3(0.0f), light_radiance);
  // Inward-facing walls.
  add_quad(s, {-1, -1, 1}, {1, -1, 1}, {1, -1, -1}, {-1, -1, -1}, white);  // floor, +y
  add_quad(s, {-1, 1, -1}, {1, 1, -1}, {1, 1, 1}, {-1, 1, 1}, white);      // ceiling, -y
  add_quad(s, {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, white);  // back, +z
  add_quad(s, {-1, -1, 1}, {-1, -1, -1}, {-1, 1, -1}, {-1, 1, 1}, red);    // left, +x
  add_quad(s, {1, -1, -1}, {1, -1, 1}, {1, 1, 1}, {1, 1, -1}, green);      // right, -x
  add_quad(s, {-1, -1, 1}, {-1, 1, 1}, {1, 1, 1}, {1, -1, 1}, white);      // front, -z: closes the box
  add_quad(s, {-0.25f, 0.99f, -0.25f}, {0.25f, 0.99f, -0.25f}, {0.25f, 0.99f, 0.25f}, {-0.25f, 0.99f, 0.25f}, light);
  add_block(s, {-0.6f, -1.0f, -0.5f}, {-0.1f, 0.2f, 0.0f}, white);
  add_block(s, {0.15f, -1.0f, 0.0f}, {0.65f, -0.45f, 0.5f}, white);
  // The camera sits inside the closed box, near the front wall.
  s.views.push_back({"front", scenes::Camera::look_at({0.0f, 0.0f, 0.95f}, {0.0f, 0.0f, -1.0f}, {0, 1, 0}, 1.2f), -1});
  s.derive();
  return s;
}

scenes::Scene textured_box() {
  scenes::Scene s = cornell_box();
  // Floor: a 4 x 4 checker of two colours, repeated twice across the floor, bilinear.
  const int floor = add_material(s, glm::vec3(1.0f));
  s.materials[floor].base_color_texture = add_texture(s, 4, 4, [](int x, int y) {
    return (x + y) % 2 ? glm::vec4(0.8f, 0.7f, 0.2f, 1.0f) : glm::vec4(0.15f, 0.3f, 0.6f, 1.0f);
  });
  s.meshes[0].material = floor;
  s.meshes[0].uvs = {{0.0f, 0.0f}, {2.0f, 0.0f}, {2.0f, 2.0f}, {0.0f, 2.0f}};
  // Back wall: ridges along u in the normal map (tilted +-0.5 in tangent space), glossy
  // where the metallic-roughness texture says so.
  const int wall = add_material(s, glm::vec3(0.7f));
  scenes::Material& w = s.materials[wall];
  w.normal_texture = add_texture(s, 8, 1, [](int x, int) {
    const float tilt = 0.5f * std::sin(2.0f * float(M_PI) * (float(x) + 0.5f) / 8.0f);
    const glm::vec3 n = glm::normalize(glm::vec3(tilt, 0.0f, 1.0f));
    return glm::vec4(0.5f * n + 0.5f, 1.0f);
  });
  w.metallic = 1.0f;  // times the texture's B
  w.specular = 1.0f;
  w.metallic_roughness_texture = add_texture(s, 2, 2, [](int x, int y) {
    return glm::vec4(0.0f, (x + y) % 2 ? 0.9f : 0.35f, (x + y) % 2 ? 0.0f : 0.6f, 1.0f);
  }, scenes::Filter::Nearest);
  s.meshes[2].material = wall;
  s.meshes[2].uvs = {{0.0f, 0.0f}, {2.0f, 0.0f}, {2.0f, 2.0f}, {0.0f, 2.0f}};
  // Light: an emissive texture of four tints (nearest), on the quad's UVs.
  scenes::Material& light = s.materials[size_t(s.meshes[6].material)];
  light.emissive_texture = add_texture(s, 2, 2, [](int x, int y) {
    return x + y == 0 ? glm::vec4(1.0f) : x == y ? glm::vec4(0.4f, 0.8f, 1.0f, 1.0f) : glm::vec4(1.0f, 0.6f, 0.5f, 1.0f);
  }, scenes::Filter::Nearest);
  s.meshes[6].uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
  // A grating 0.3 under the light: alpha 1 on even texel columns, 0 on odd ones (nearest).
  const int grating = add_material(s, glm::vec3(0.73f));
  scenes::Material& g = s.materials[grating];
  g.alpha_mode = scenes::AlphaMode::Mask;
  g.alpha_cutoff = 0.5f;
  g.double_sided = true;
  g.base_color_texture = add_texture(s, 6, 1, [](int x, int) {
    return glm::vec4(0.9f, 0.9f, 0.9f, x % 2 ? 0.0f : 1.0f);
  }, scenes::Filter::Nearest);
  add_textured_quad(s, {-0.4f, 0.69f, 0.4f}, {0.4f, 0.69f, 0.4f}, {0.4f, 0.69f, -0.4f}, {-0.4f, 0.69f, -0.4f}, grating);
  s.derive();
  return s;
}

scenes::Scene cornell_box_every_light() {
  scenes::Scene s = cornell_box();
  scenes::Light spot;
  spot.type = scenes::LightType::Spot;
  spot.position = {0.5f, 0.8f, 0.5f};
  spot.direction = glm::normalize(glm::vec3(-0.5f, -1.0f, -0.6f));
  spot.intensity = 3.0f;
  scenes::Light sun;
  sun.type = scenes::LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
  sun.intensity = 2.0f;
  s.lights = {spot, sun};
  s.derive();
  return s;
}

scenes::Scene lit_textured_box() {
  scenes::Scene s = textured_box();
  scenes::Light point;
  point.type = scenes::LightType::Point;
  point.position = {0.3f, 0.5f, 0.2f};
  point.intensity = 2.0f;
  s.lights = {point};
  s.derive();
  return s;
}

scenes::Scene scaled(scenes::Scene s, float k) {
  for (scenes::Mesh& m : s.meshes)
    for (glm::vec3& p : m.positions) p *= k;
  for (scenes::Light& l : s.lights) l.position *= k;
  for (scenes::View& v : s.views) {
    v.camera.position *= k;
    v.camera.znear *= k;
  }
  s.derive();
  return s;
}

scenes::Scene lambert_plane(float rho, float half, float eye_height) {
  scenes::Scene s;
  const int m = add_material(s, glm::vec3(rho));
  add_quad(s, {-half, 0, half}, {half, 0, half}, {half, 0, -half}, {-half, 0, -half}, m);
  s.views.push_back({"top", scenes::Camera::look_at({0.0f, eye_height, 0.0f}, {0.0f, 0.0f, 0.0f}, {0, 0, -1}, 1.0471976f), -1});
  s.derive();
  return s;
}

// A UV sphere of `rings` x `segments` quads; many thin triangles meeting at shared edges and
// at the poles, which is where ray tracers disagree on ties.
void add_sphere(scenes::Scene& s, glm::vec3 c, float r, int rings, int segments, int material) {
  scenes::Mesh m;
  m.name = "sphere";
  m.object_id = uint32_t(s.meshes.size() + 1);
  m.material = material;
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j <= segments; ++j) {
      const float th = float(M_PI) * float(i) / float(rings), ph = 2.0f * float(M_PI) * float(j) / float(segments);
      const glm::vec3 n(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
      m.positions.push_back(c + r * n);
      m.normals.push_back(n);
    }
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const uint32_t a = uint32_t(i * (segments + 1) + j), b = a + 1, d = a + uint32_t(segments + 1), e = d + 1;
      if (i > 0) m.triangles.push_back({a, b, d});
      if (i + 1 < rings) m.triangles.push_back({b, e, d});
    }
  s.meshes.push_back(std::move(m));
}

}  // namespace giq::test
