// Fitting a declared area light shape (Mesh::area_shape) to the emitter's posed triangles, each
// frame: what real-time techniques need for the representative point of glossy reflections
// (Karis 2013, "Real Shading in Unreal Engine 4", "Area Lights"; Turánszki 2017, "Area Lights").
// The triangles stay what every renderer integrates for diffuse light and what the reference
// samples; only the glossy term reads the shape.

#include <algorithm>
#include <cmath>

#include "giq/scenes/scene.h"

namespace giq::scenes {
namespace {

// The unit direction along which the points spread most: the covariance's principal
// eigenvector, by power iteration from the coordinate axis of largest variance.
glm::vec3 principal_axis(const std::vector<glm::vec3>& points, glm::vec3 centre) {
  glm::dmat3 c(0.0);
  for (const glm::vec3& p : points) {
    const glm::dvec3 d = glm::dvec3(p - centre);
    c += glm::outerProduct(d, d);
  }
  glm::dvec3 v(0.0);
  v[c[0][0] >= c[1][1] && c[0][0] >= c[2][2] ? 0 : c[1][1] >= c[2][2] ? 1 : 2] = 1.0;
  for (int i = 0; i < 64; ++i) {
    const glm::dvec3 w = c * v;
    const double len = glm::length(w);
    if (!(len > 0.0)) break;
    v = w / len;
  }
  return glm::vec3(v);
}

}  // namespace

void fit_area_shape(const Mesh& mesh, const std::vector<EmissiveTriangle>& emissive, AreaLight& l) {
  l.shape = mesh.area_shape;
  if (l.shape == AreaShape::Mesh) return;
  std::vector<glm::vec3> points;
  for (const uint32_t i : l.triangles) {
    const glm::uvec3 t = mesh.triangles[emissive[i].triangle];
    points.insert(points.end(), {mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]});
  }
  const glm::vec3 c = l.centroid;
  l.shape_centre = c;
  const auto mean_of = [&](auto f) {
    double s = 0.0;
    for (const glm::vec3& p : points) s += f(p);
    return float(s / double(points.size()));
  };
  switch (l.shape) {
    case AreaShape::Mesh:
      break;
    case AreaShape::Sphere:
      // Tessellated spheres have their vertices on the sphere.
      l.shape_radius = mean_of([&](glm::vec3 p) { return glm::length(p - c); });
      break;
    case AreaShape::Disc:
      if (!l.flat) {
        l.shape = AreaShape::Mesh;
        break;
      }
      for (const glm::vec3& p : points) {
        const glm::vec3 d = p - c;
        l.shape_radius = std::max(l.shape_radius, glm::length(d - l.normal * glm::dot(d, l.normal)));
      }
      l.shape_v = l.normal;
      break;
    case AreaShape::Rectangle: {
      if (!l.flat) {
        l.shape = AreaShape::Mesh;
        break;
      }
      // The smallest rectangle with a side along one of the triangles' edges (a rectangle's
      // own sides are among them; its diagonals give larger ones).
      float best = INFINITY;
      for (size_t k = 0; k < points.size(); ++k) {
        glm::vec3 u = points[k % 3 == 2 ? k - 2 : k + 1] - points[k];
        u -= l.normal * glm::dot(u, l.normal);
        if (!(glm::length(u) > 0.0f)) continue;
        u = glm::normalize(u);
        const glm::vec3 v = glm::cross(l.normal, u);
        glm::vec2 lo(INFINITY), hi(-INFINITY);
        for (const glm::vec3& p : points) {
          const glm::vec2 q(glm::dot(p - c, u), glm::dot(p - c, v));
          lo = glm::min(lo, q), hi = glm::max(hi, q);
        }
        const glm::vec2 half = 0.5f * (hi - lo);
        if (half.x * half.y < best) {
          best = half.x * half.y;
          l.shape_centre = c + u * (0.5f * (lo.x + hi.x)) + v * (0.5f * (lo.y + hi.y));
          l.shape_u = u * half.x, l.shape_v = v * half.y;
        }
      }
      break;
    }
    case AreaShape::Tube: {
      // A capsule: the segment along the points' principal axis, swept by the largest distance
      // from that axis (the cylinder's; cap vertices lie closer); the caps reach one radius
      // past the segment's ends.
      const glm::vec3 a = principal_axis(points, c);
      float lo = INFINITY, hi = -INFINITY;
      for (const glm::vec3& p : points) {
        const glm::vec3 d = p - c;
        lo = std::min(lo, glm::dot(d, a)), hi = std::max(hi, glm::dot(d, a));
        l.shape_radius = std::max(l.shape_radius, glm::length(d - a * glm::dot(d, a)));
      }
      l.shape_centre = c + a * (0.5f * (lo + hi));
      l.shape_u = a * std::max(0.0f, 0.5f * (hi - lo) - l.shape_radius);
      break;
    }
  }
}

}  // namespace giq::scenes
