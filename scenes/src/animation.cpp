// Keyframe interpolation and node transforms over time (glTF 2.0 spec, 3.11 "Animations",
// and Appendix C "Animation Sampler Interpolation Modes").

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "scene_source.h"

namespace giq::scenes {
namespace {

// Appendix C, "Spherical Linear Interpolation": shortest arc between unit quaternions.
glm::dvec4 slerp(glm::dvec4 a, glm::dvec4 b, double s) {
  double d = glm::dot(a, b);
  if (d < 0.0) b = -b, d = -d;
  if (d > 1.0 - 1e-12) return glm::normalize(glm::mix(a, b, s));  // nearly equal: sin(angle) ~ 0
  const double angle = std::acos(d);
  const double sa = std::sin(angle);
  return a * (std::sin(angle * (1.0 - s)) / sa) + b * (std::sin(angle * s) / sa);
}

}  // namespace

glm::dvec4 evaluate(const ChannelSource& c, double t) {
  const size_t n = c.times.size();
  const bool cubic = c.interpolation == Interpolation::CubicSpline;
  auto value = [&](size_t k) { return cubic ? c.values[3 * k + 1] : c.values[k]; };
  glm::dvec4 v;
  if (!(t > c.times.front())) {
    v = value(0);  // before the first key (or NaN t): the first value
  } else if (t >= c.times.back()) {
    v = value(n - 1);
  } else {
    const size_t k = size_t(std::upper_bound(c.times.begin(), c.times.end(), t) - c.times.begin()) - 1;
    const double td = c.times[k + 1] - c.times[k];
    const double s = (t - c.times[k]) / td;
    switch (c.interpolation) {
      case Interpolation::Step:
        v = value(k);
        break;
      case Interpolation::Linear:
        v = c.path == AnimatedPath::Rotation ? slerp(value(k), value(k + 1), s) : glm::mix(value(k), value(k + 1), s);
        break;
      case Interpolation::CubicSpline: {
        // Appendix C, "Cubic Spline Interpolation": Hermite spline with the out-tangent b_k of
        // key k and the in-tangent a_{k+1} of key k+1, both scaled by the key interval.
        const double s2 = s * s, s3 = s2 * s;
        const glm::dvec4 vk = c.values[3 * k + 1], bk = c.values[3 * k + 2];
        const glm::dvec4 vk1 = c.values[3 * (k + 1) + 1], ak1 = c.values[3 * (k + 1)];
        v = (2 * s3 - 3 * s2 + 1) * vk + td * (s3 - 2 * s2 + s) * bk + (-2 * s3 + 3 * s2) * vk1 + td * (s3 - s2) * ak1;
        break;
      }
    }
  }
  if (c.path == AnimatedPath::Rotation) {
    const double len = glm::length(v);
    v = len > 0.0 ? v / len : glm::dvec4(0, 0, 0, 1);  // "normalised after cubic" (Appendix C)
  }
  return v;
}

std::vector<glm::dmat4> world_transforms(const SceneSource& src, int animation, double t) {
  std::vector<glm::dvec3> translation(src.nodes.size()), scale(src.nodes.size());
  std::vector<glm::dquat> rotation(src.nodes.size());
  for (size_t i = 0; i < src.nodes.size(); ++i)
    translation[i] = src.nodes[i].translation, rotation[i] = src.nodes[i].rotation, scale[i] = src.nodes[i].scale;
  if (animation >= 0 && size_t(animation) < src.animations.size()) {
    for (const auto& c : src.animations[size_t(animation)].channels) {
      const glm::dvec4 v = evaluate(c, t);
      switch (c.path) {
        case AnimatedPath::Translation: translation[size_t(c.node)] = glm::dvec3(v); break;
        case AnimatedPath::Rotation: rotation[size_t(c.node)] = glm::dquat(v.w, v.x, v.y, v.z); break;
        case AnimatedPath::Scale: scale[size_t(c.node)] = glm::dvec3(v); break;
      }
    }
  }
  std::vector<glm::dmat4> world(src.nodes.size(), glm::dmat4(1.0));
  // Parents before children: the hierarchy was checked to be a forest, so a stack walk from
  // the roots reaches every instantiated node exactly once.
  std::vector<int> stack(src.roots.rbegin(), src.roots.rend());
  while (!stack.empty()) {
    const int i = stack.back();
    stack.pop_back();
    const NodeSource& n = src.nodes[size_t(i)];
    // glTF 2.0 spec, 3.5.3 "Transformations": local = T * R * S, or the matrix when given.
    const glm::dmat4 local = n.has_matrix ? n.matrix
                                          : glm::translate(glm::dmat4(1.0), translation[size_t(i)]) * glm::mat4_cast(rotation[size_t(i)]) *
                                                glm::scale(glm::dmat4(1.0), scale[size_t(i)]);
    world[size_t(i)] = n.parent >= 0 ? world[size_t(n.parent)] * local : local;
    for (auto it = n.children.rbegin(); it != n.children.rend(); ++it) stack.push_back(*it);
  }
  return world;
}

}  // namespace giq::scenes
