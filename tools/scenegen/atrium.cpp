// `atrium`: a large textured hall for load, memory and speed benchmarks (bench/scenes): a nave
// lit by the sun through a skylight, two arcades of round columns under semicircular arches,
// thin wavy curtains hung in one arcade, and a sealed sacristy behind a thin east wall whose
// truth is black (its surfaces are leak regions). Every surface is textured (base colour,
// metallic-roughness and a normal map made from the same height field), with
// AtriumDetail::materials materials of three textures each. The detail decides the triangle
// count and texture size: the benchmark's takes over a million triangles and a hundred 2048²
// textures.

#include <cmath>
#include <numbers>

#include "scenes.h"
#include "text.h"

namespace giq::scenegen {
namespace {

constexpr double kPi = std::numbers::pi;
// The hall's interior: x in [-kHalfLength, kHalfLength], z in [-kHalfWidth, kHalfWidth].
constexpr double kHalfLength = 12.0, kHalfWidth = 8.0, kHeight = 9.0;
constexpr double kThinWall = 0.02;   // the east wall, between the hall and the sacristy
constexpr double kSacristy = 3.0;    // the sacristy's depth beyond it (x)
constexpr double kArcadeZ = 4.0;     // |z| of the two rows of columns
constexpr double kColumnRadius = 0.45, kColumnHeight = 5.0;
constexpr int kColumnsPerRow = 6;    // at x = -10, -6, ..., 10
constexpr double kArchThickness = 0.6;
const glm::dvec3 kSunDirection{0.35, -1.0, 0.25};
constexpr double kSunIrradiance = 20.0;  // W/m^2 facing the sun

double column_x(int i) { return -10.0 + 4.0 * i; }

// A deterministic hash of integers to [0, 1).
double hash01(uint32_t a, uint32_t b, uint32_t c) {
  uint32_t h = a * 0x9E3779B1u ^ (b + 0x7F4A7C15u) * 0x85EBCA77u ^ (c + 0x165667B1u) * 0xC2B2AE3Du;
  h ^= h >> 15, h *= 0x2C1B3C6Du, h ^= h >> 12, h *= 0x297A2D39u, h ^= h >> 15;
  return double(h >> 8) / double(1u << 24);
}

// Value noise on a periodic lattice of `period` cells (tiles seamlessly under REPEAT).
double noise(double x, double y, int period, uint32_t seed) {
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const double fx = x - x0, fy = y - y0;
  auto at = [&](int i, int j) {
    return hash01(uint32_t(((i % period) + period) % period), uint32_t(((j % period) + period) % period), seed);
  };
  const double sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
  return (at(x0, y0) * (1 - sx) + at(x0 + 1, y0) * sx) * (1 - sy) + (at(x0, y0 + 1) * (1 - sx) + at(x0 + 1, y0 + 1) * sx) * sy;
}

// A material's height field at (u, v) in [0, 1)^2 and its colour: tiles, marble, fabric or
// bricks by `kind`, tinted by `hue`.
struct Texel {
  double height;
  glm::dvec3 colour;
  double roughness;
};
Texel pattern(int kind, double u, double v, glm::dvec3 hue, uint32_t seed) {
  const double grain = 0.15 * noise(u * 64, v * 64, 64, seed);
  switch (kind % 4) {
    case 0: {  // square tiles with grout
      const double fu = u * 4 - std::floor(u * 4), fv = v * 4 - std::floor(v * 4);
      const bool grout = fu < 0.04 || fv < 0.04;
      const double tile = hash01(uint32_t(u * 4), uint32_t(v * 4), seed);
      return {grout ? 0.0 : 1.0 - grain, grout ? glm::dvec3(0.35) : hue * (0.7 + 0.3 * tile) * (1.0 - grain), grout ? 0.9 : 0.35};
    }
    case 1: {  // marble: veins of turbulent sine
      double t = 0;
      for (int o = 0; o < 4; ++o) t += noise(u * (4 << o), v * (4 << o), 4 << o, seed + o) / double(1 << o);
      const double vein = std::pow(std::abs(std::sin((u * 3 + t * 1.5) * kPi)), 0.3);
      return {vein, glm::mix(glm::dvec3(0.25), hue, vein), 0.2 + 0.2 * (1 - vein)};
    }
    case 2: {  // woven fabric
      const double a = std::sin(u * 128 * kPi), b = std::sin(v * 128 * kPi);
      const double h = 0.5 + 0.25 * (a > 0 ? a : b);
      return {h, hue * (0.6 + 0.4 * h), 0.85};
    }
    default: {  // running-bond bricks
      const double rows = v * 8, row = std::floor(rows);
      const double cols = u * 4 + (int(row) % 2 ? 0.5 : 0.0), col = std::floor(cols);
      const bool mortar = rows - row < 0.08 || cols - col < 0.05;
      const double shade = hash01(uint32_t(col), uint32_t(row), seed);
      return {mortar ? 0.0 : 0.8 + grain, mortar ? glm::dvec3(0.6) : hue * (0.6 + 0.4 * shade), mortar ? 0.95 : 0.7};
    }
  }
}

uint8_t unorm(double x) { return uint8_t(std::lround(std::clamp(x, 0.0, 1.0) * 255.0)); }
// IEC 61966-2-1 encoding of a linear value: glTF base colour textures are sRGB.
uint8_t srgb(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return unorm(x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055);
}

// Adds material k's three textures and the material itself.
int add_textured_material(GltfWriter& g, int k, int size, bool double_sided) {
  const glm::dvec3 hue(0.45 + 0.4 * hash01(k, 1, 7), 0.45 + 0.4 * hash01(k, 2, 7), 0.45 + 0.4 * hash01(k, 3, 7));
  const size_t n = size_t(size) * size_t(size);
  std::vector<double> height(n);
  std::vector<uint8_t> base(4 * n), mr(4 * n), normal(4 * n);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const size_t i = size_t(y) * size_t(size) + size_t(x);
      const Texel t = pattern(double_sided ? 2 : k, (x + 0.5) / size, (y + 0.5) / size, hue, uint32_t(k));
      height[i] = t.height;
      base[4 * i] = srgb(t.colour.r), base[4 * i + 1] = srgb(t.colour.g), base[4 * i + 2] = srgb(t.colour.b), base[4 * i + 3] = 255;
      mr[4 * i] = 255, mr[4 * i + 1] = unorm(t.roughness), mr[4 * i + 2] = 0, mr[4 * i + 3] = 255;
    }
  // Tangent-space normals from the height field's central differences (wrapping, as the
  // texture repeats); the bump depth is a fixed fraction of a texel's size at 256².
  const double depth = 4.0 * size / 256.0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      auto h = [&](int i, int j) { return height[size_t((j + size) % size) * size_t(size) + size_t((i + size) % size)]; };
      const glm::dvec3 nrm = glm::normalize(glm::dvec3(-(h(x + 1, y) - h(x - 1, y)) * depth, (h(x, y + 1) - h(x, y - 1)) * depth, 1.0));
      const size_t i = size_t(y) * size_t(size) + size_t(x);
      for (int c = 0; c < 3; ++c) normal[4 * i + size_t(c)] = unorm(0.5 * nrm[c] + 0.5);
      normal[4 * i + 3] = 255;
    }
  const std::string name = "surface" + std::to_string(k);
  MaterialSpec m{name, glm::dvec3(1.0), 0.0, 1.0, {}, {}};
  m.base_color_texture = g.add_texture(name + "_base", size, size, base);
  m.metallic_roughness_texture = g.add_texture(name + "_mr", size, size, mr);
  m.normal_texture = g.add_texture(name + "_normal", size, size, normal);
  m.double_sided = double_sided;
  return g.add_material(m);
}

// A grid of (nu + 1) x (nv + 1) vertices at f(u, v), u, v in [0, 1], with the UVs scaled by
// `repeat`; triangles counter-clockwise seen from the side the normals n(u, v) point to.
template <class P, class N>
void add_grid(MeshData& m, int nu, int nv, glm::dvec2 repeat, P position, N normal) {
  const uint32_t base = uint32_t(m.positions.size());
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      const double u = double(i) / nu, v = double(j) / nv;
      m.positions.push_back(position(u, v));
      m.normals.push_back(glm::normalize(normal(u, v)));
      m.uvs.emplace_back(u * repeat.x, v * repeat.y);
    }
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const uint32_t a = base + uint32_t(j * (nu + 1) + i), b = a + 1, c = a + uint32_t(nu + 1), d = c + 1;
      // The first triangle's winding against the normal at its corner decides the order.
      const glm::dvec3 e = glm::cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
      if (glm::dot(e, m.normals[a]) >= 0.0) m.indices.insert(m.indices.end(), {a, b, c, b, d, c});
      else m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
    }
}

// A planar rectangle from corner o along edges eu, ev, facing `facing`, as one grid.
void add_panel(MeshData& m, glm::dvec3 o, glm::dvec3 eu, glm::dvec3 ev, glm::dvec3 facing, glm::dvec2 repeat, int nu = 1, int nv = 1) {
  const glm::dvec3 n = glm::dot(glm::cross(eu, ev), facing) >= 0.0 ? glm::normalize(glm::cross(eu, ev)) : -glm::normalize(glm::cross(eu, ev));
  add_grid(m, nu, nv, repeat, [&](double u, double v) { return o + u * eu + v * ev; }, [&](double, double) { return n; });
}

}  // namespace

BuiltinScene make_atrium(const AtriumDetail& d) {
  BuiltinScene s;
  s.name = "atrium";
  s.purpose =
      "Scale and textures: a hall of " + num(2 * kHalfLength) + " m by " + num(2 * kHalfWidth) +
      " m lit by the sun through a skylight, with two arcades of round columns under arches, thin "
      "double-sided curtains in one arcade and a sealed sacristy behind a thin east wall (its "
      "truth is black: leak regions). Every surface is textured.";
  GltfWriter& g = s.gltf;
  // Materials 0 .. n-2 go round the surfaces; the last, double-sided, is the curtains' fabric.
  std::vector<int> materials;
  for (int k = 0; k < d.materials; ++k) materials.push_back(add_textured_material(g, k, d.texture_size, k + 1 == d.materials));
  int next = 0;
  auto material = [&] { return materials[size_t(next++ % (d.materials - 1))]; };
  const glm::dvec2 metre(0.25);  // texture repeats per metre of wall

  // The hall's shell, seen from inside, one node per panel; the ceiling has the skylight.
  const double L = kHalfLength, W = kHalfWidth, H = kHeight;
  auto panel = [&](const std::string& name, glm::dvec3 o, glm::dvec3 eu, glm::dvec3 ev, glm::dvec3 facing, int n) {
    MeshData m;
    add_panel(m, o, eu, ev, facing, metre * glm::dvec2(glm::length(eu), glm::length(ev)), n, n);
    g.add_mesh_node(name, m, material());
  };
  panel("floor", {-L, 0, -W}, {2 * L, 0, 0}, {0, 0, 2 * W}, {0, 1, 0}, d.panel);
  panel("wall_south", {-L, 0, -W}, {2 * L, 0, 0}, {0, H, 0}, {0, 0, 1}, d.panel);
  panel("wall_north", {-L, 0, W}, {2 * L, 0, 0}, {0, H, 0}, {0, 0, -1}, d.panel);
  panel("wall_west", {-L, 0, -W}, {0, 0, 2 * W}, {0, H, 0}, {1, 0, 0}, d.panel);
  panel("wall_east", {L, 0, -W}, {0, 0, 2 * W}, {0, H, 0}, {-1, 0, 0}, d.panel);
  // Ceiling: four panels round a skylight of x in [-6, 6], z in [-2, 2]. Seen from above they
  // are backs of one-sided surfaces, which stop the sun everywhere but through the skylight.
  const glm::dvec3 down(0, -1, 0);
  panel("ceiling_south", {-L, H, -W}, {2 * L, 0, 0}, {0, 0, W - 2}, down, 1);
  panel("ceiling_north", {-L, H, 2}, {2 * L, 0, 0}, {0, 0, W - 2}, down, 1);
  panel("ceiling_west", {-L, H, -2}, {L - 6, 0, 0}, {0, 0, 4}, down, 1);
  panel("ceiling_east", {6, H, -2}, {L - 6, 0, 0}, {0, 0, 4}, down, 1);

  // The sacristy: a sealed room beyond the east wall (x from L + kThinWall), its surfaces
  // facing in, and the thin wall's east face.
  {
    const double x0 = L + kThinWall, x1 = x0 + kSacristy, z0 = -2.0, z1 = 2.0, h = 4.0;
    const glm::dvec3 lo(x0, 0, z0), hi(x1, h, z1), inside = (lo + hi) * 0.5;
    const std::array<Quad, 6> q = box_quads(lo, hi);
    const char* names[6] = {"sacristy_floor", "sacristy_ceiling", "sacristy_west", "sacristy_east", "sacristy_south", "sacristy_north"};
    const int m = material();
    for (int f = 0; f < 6; ++f) {
      MeshData face;
      const Quad& c = q[size_t(f)];
      const glm::dvec3 n = glm::normalize(inside - centroid(c));
      add_panel(face, c[0], c[1] - c[0], c[3] - c[0], n, glm::dvec2(1.0), d.panel / 4 + 1, d.panel / 4 + 1);
      g.add_mesh_node(names[f], face, m);
      g.add_leak_region(names[f]);
    }
  }

  // Two arcades of columns (cylinders of column_segments x column_rings quads) under
  // semicircular arches spanning neighbouring columns.
  for (int row = 0; row < 2; ++row) {
    const double z = row == 0 ? -kArcadeZ : kArcadeZ;
    for (int i = 0; i < kColumnsPerRow; ++i) {
      const glm::dvec3 c(column_x(i), 0, z);
      MeshData m;
      add_grid(
          m, d.column_segments, d.column_rings, {2.0, 4.0},
          [&](double u, double v) {
            return c + glm::dvec3(kColumnRadius * std::cos(2 * kPi * u), kColumnHeight * v, -kColumnRadius * std::sin(2 * kPi * u));
          },
          [&](double u, double) { return glm::dvec3(std::cos(2 * kPi * u), 0, -std::sin(2 * kPi * u)); });
      g.add_mesh_node("column_" + std::to_string(row) + "_" + std::to_string(i), m, material());
    }
    for (int i = 0; i + 1 < kColumnsPerRow; ++i) {
      const double x0 = column_x(i), x1 = column_x(i + 1), mid = 0.5 * (x0 + x1);
      const double r_in = 0.5 * (x1 - x0) - kColumnRadius, r_out = 0.5 * (x1 - x0) + 0.1;
      const double zf = z - 0.5 * kArchThickness, zb = z + 0.5 * kArchThickness;
      const int n = d.arch_segments;
      MeshData m;
      auto arc = [&](double r, double t, double zz) { return glm::dvec3(mid - r * std::cos(kPi * t), kColumnHeight + r * std::sin(kPi * t), zz); };
      // Intrados (facing down towards the arch's centre) and extrados (up and out).
      add_grid(m, n, 2, {4.0, 1.0}, [&](double t, double v) { return arc(r_in, t, zf + v * kArchThickness); },
               [&](double t, double) { return -glm::dvec3(-std::cos(kPi * t), std::sin(kPi * t), 0); });
      add_grid(m, n, 2, {4.0, 1.0}, [&](double t, double v) { return arc(r_out, t, zf + v * kArchThickness); },
               [&](double t, double) { return glm::dvec3(-std::cos(kPi * t), std::sin(kPi * t), 0); });
      // Both faces of the half ring.
      for (const double zz : {zf, zb}) {
        const glm::dvec3 facing(0, 0, zz < z ? -1 : 1);
        add_grid(m, n, 2, {4.0, 1.0}, [&](double t, double v) { return arc(r_in + v * (r_out - r_in), t, zz); },
                 [&](double, double) { return facing; });
      }
      g.add_mesh_node("arch_" + std::to_string(row) + "_" + std::to_string(i), m, material());
    }
  }

  // Thin curtains hung in the north arcade between the middle columns: wavy double-sided
  // sheets, 1 cm apart in pairs, down to 5 cm above the floor.
  for (int i = 1; i + 2 < kColumnsPerRow; ++i) {
    const double x0 = column_x(i) + kColumnRadius, x1 = column_x(i + 1) - kColumnRadius;
    MeshData m;
    for (const double offset : {-0.005, 0.005}) {
      add_grid(
          m, d.curtain_folds, d.curtain_rows, {4.0, 4.0},
          [&](double u, double v) {
            return glm::dvec3(x0 + u * (x1 - x0), 0.05 + v * (kColumnHeight - 0.05), kArcadeZ + 0.35 + offset + 0.08 * std::sin(12 * kPi * u));
          },
          [&](double u, double) { return glm::dvec3(-0.08 * 12 * kPi * std::cos(12 * kPi * u) / (x1 - x0), 0, 1); });
    }
    g.add_mesh_node("curtain_" + std::to_string(i), m, materials.back());
  }

  g.add_light_node({"sun", LightKind::Directional, glm::dvec3(1.0, 0.95, 0.85), kSunIrradiance},
                   {glm::dvec3(0.0, H + 2.0, 0.0), rotation_from_minus_z(kSunDirection)});
  const double aspect = 16.0 / 9.0;
  g.add_camera_node({"nave", {-11.0, 1.7, 0.0}, {6.0, 3.0, 0.0}, {0, 1, 0}, 60.0}, aspect, 0.05);
  g.add_view({"aisle", {-11.0, 1.6, 6.5}, {8.0, 2.0, 5.5}, {0, 1, 0}, 60.0});
  g.add_view({"curtains", {-3.0, 1.5, 0.5}, {-1.0, 2.0, 4.3}, {0, 1, 0}, 60.0});
  g.add_view({"sacristy", {L + 2.7, 1.6, 1.7}, {L + 0.5, 1.2, -1.0}, {0, 1, 0}, 70.0});

  s.notes = {
      "Hall: " + num(2 * L) + " x " + num(H) + " x " + num(2 * W) + " m inside (x, y, z), a skylight of 12 x 4 m in the ceiling; the sun (" +
          num(kSunIrradiance) + " W/m^2 facing it) travels along " + vec(glm::normalize(kSunDirection), 3) + ".",
      "Arcades at z = +-" + num(kArcadeZ) + " m: " + std::to_string(kColumnsPerRow) + " columns each (radius " + num(kColumnRadius) +
          " m, " + num(kColumnHeight) + " m tall), semicircular arches between them.",
      "Curtains: pairs of wavy double-sided sheets 1 cm apart in the north arcade.",
      "Sacristy: a sealed room beyond a " + num(kThinWall * 100) + " cm east wall; its six surfaces are leak regions and its truth is black.",
      "Materials: " + std::to_string(d.materials) + " procedural ones (tiles, marble, fabric, bricks), each with a base colour, a "
          "metallic-roughness and a normal texture of " + std::to_string(d.texture_size) + "^2 texels.",
  };
  return s;
}

}  // namespace giq::scenegen
