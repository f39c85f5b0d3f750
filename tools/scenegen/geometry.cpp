#include "geometry.h"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace giq::scenegen {
namespace {

// Two unit normals closer than this (in double precision) are the same plane: the published
// Cornell data are given to 0.1 mm, so a truly non-planar quad differs by far more.
constexpr double kPlanarTolerance = 1e-12;

glm::dvec3 triangle_normal(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double len = glm::length(n);
  if (!(len > 1e-12)) throw std::invalid_argument("degenerate triangle in a built-in scene");
  return n / len;
}

void append_triangle(MeshData& mesh, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  const glm::dvec3 n = triangle_normal(a, b, c);
  const auto base = static_cast<uint32_t>(mesh.positions.size());
  for (glm::dvec3 p : {a, b, c}) {
    mesh.positions.push_back(p);
    mesh.normals.push_back(n);
  }
  mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
}

}  // namespace

glm::dvec3 centroid(const Quad& q) {
  return (q[0] + q[1] + q[2] + q[3]) * 0.25;
}

void add_quad(MeshData& mesh, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, glm::dvec3 d,
              glm::dvec3 facing) {
  // Newell's normal of the polygon decides the winding, robust for slightly non-planar quads.
  const glm::dvec3 newell = glm::cross(c - a, d - b);
  const double along = glm::dot(newell, facing);
  if (!(std::abs(along) > 1e-12 * glm::length(newell) * glm::length(facing)))
    throw std::invalid_argument("quad facing lies in the quad's plane");
  if (along < 0.0) std::swap(b, d);  // reverse the cyclic order a-b-c-d into a-d-c-b

  const glm::dvec3 n1 = triangle_normal(a, b, c);
  const glm::dvec3 n2 = triangle_normal(a, c, d);
  if (glm::length(n1 - n2) > kPlanarTolerance) {
    append_triangle(mesh, a, b, c);
    append_triangle(mesh, a, c, d);
    return;
  }
  const auto base = static_cast<uint32_t>(mesh.positions.size());
  for (glm::dvec3 p : {a, b, c, d}) {
    mesh.positions.push_back(p);
    mesh.normals.push_back(n1);
  }
  mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

void add_quad_facing_point(MeshData& mesh, const Quad& q, glm::dvec3 inside) {
  add_quad(mesh, q[0], q[1], q[2], q[3], inside - centroid(q));
}

void add_quad_away_from(MeshData& mesh, const Quad& q, glm::dvec3 centre) {
  add_quad(mesh, q[0], q[1], q[2], q[3], centroid(q) - centre);
}

std::array<Quad, 6> box_quads(glm::dvec3 lo, glm::dvec3 hi) {
  const double x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x, y1 = hi.y, z1 = hi.z;
  if (!(x0 < x1 && y0 < y1 && z0 < z1)) throw std::invalid_argument("empty box");
  std::array<Quad, 6> q;
  q[kYLo] = {{{x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}}};
  q[kYHi] = {{{x0, y1, z0}, {x1, y1, z0}, {x1, y1, z1}, {x0, y1, z1}}};
  q[kXLo] = {{{x0, y0, z0}, {x0, y1, z0}, {x0, y1, z1}, {x0, y0, z1}}};
  q[kXHi] = {{{x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1}}};
  q[kZLo] = {{{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}}};
  q[kZHi] = {{{x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}}};
  return q;
}

void add_box(MeshData& mesh, glm::dvec3 lo, glm::dvec3 hi) {
  const glm::dvec3 centre = (lo + hi) * 0.5;
  for (const Quad& q : box_quads(lo, hi)) add_quad_away_from(mesh, q, centre);
}

void add_rect_with_hole(MeshData& mesh, glm::dvec3 lo, glm::dvec3 hi, glm::dvec3 hole_lo,
                        glm::dvec3 hole_hi, glm::dvec3 facing) {
  int plane = -1;
  for (int i = 0; i < 3; ++i)
    if (lo[i] == hi[i]) plane = i;
  if (plane < 0 || hole_lo[plane] != lo[plane] || hole_hi[plane] != lo[plane])
    throw std::invalid_argument("rectangle and hole must lie in one axis plane");
  const int u = plane == 0 ? 1 : 0;
  const int v = plane == 2 ? 1 : 2;
  if (!(lo[u] < hole_lo[u] && hole_lo[u] < hole_hi[u] && hole_hi[u] < hi[u] && lo[v] < hole_lo[v] &&
        hole_lo[v] < hole_hi[v] && hole_hi[v] < hi[v]))
    throw std::invalid_argument("hole must lie strictly inside the rectangle");

  auto point = [&](double pu, double pv) {
    glm::dvec3 p(0.0);
    p[plane] = lo[plane];
    p[u] = pu;
    p[v] = pv;
    return p;
  };
  auto rect = [&](double u0, double v0, double u1, double v1) {
    add_quad(mesh, point(u0, v0), point(u1, v0), point(u1, v1), point(u0, v1), facing);
  };
  rect(lo[u], lo[v], hi[u], hole_lo[v]);            // below the hole, full width
  rect(lo[u], hole_hi[v], hi[u], hi[v]);            // above the hole, full width
  rect(lo[u], hole_lo[v], hole_lo[u], hole_hi[v]);  // beside it, one side
  rect(hole_hi[u], hole_lo[v], hi[u], hole_hi[v]);  // and the other
}

}  // namespace giq::scenegen
