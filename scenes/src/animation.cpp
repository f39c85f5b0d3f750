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

bool ChannelSource::varies() const {
  return std::any_of(values.begin(), values.end(), [&](double v) { return v != values.front(); });
}

std::vector<double> evaluate(const ChannelSource& c, double t) {
  const size_t n = c.times.size(), w = size_t(c.width);
  const bool cubic = c.interpolation == Interpolation::CubicSpline;
  // Key k's value, in-tangent and out-tangent (the last two CUBICSPLINE only).
  auto value = [&](size_t k) { return &c.values[(cubic ? 3 * k + 1 : k) * w]; };
  auto in_tangent = [&](size_t k) { return &c.values[3 * k * w]; };
  auto out_tangent = [&](size_t k) { return &c.values[(3 * k + 2) * w]; };
  std::vector<double> v(w);
  if (!(t > c.times.front())) {
    std::copy_n(value(0), w, v.begin());  // before the first key (or NaN t): the first value
  } else if (t >= c.times.back()) {
    std::copy_n(value(n - 1), w, v.begin());
  } else {
    const size_t k = size_t(std::upper_bound(c.times.begin(), c.times.end(), t) - c.times.begin()) - 1;
    const double td = c.times[k + 1] - c.times[k];
    const double s = (t - c.times[k]) / td;
    const double *a = value(k), *b = value(k + 1);
    switch (c.interpolation) {
      case Interpolation::Step:
        std::copy_n(a, w, v.begin());
        break;
      case Interpolation::Linear:
        if (c.path == AnimatedPath::Rotation) {
          const glm::dvec4 q = slerp(glm::dvec4(a[0], a[1], a[2], a[3]), glm::dvec4(b[0], b[1], b[2], b[3]), s);
          for (int j = 0; j < 4; ++j) v[size_t(j)] = q[j];
        } else {
          for (size_t j = 0; j < w; ++j) v[j] = a[j] * (1.0 - s) + b[j] * s;  // glm::mix's rounding, as before
        }
        break;
      case Interpolation::CubicSpline: {
        // Appendix C, "Cubic Spline Interpolation": Hermite spline with the out-tangent b_k of
        // key k and the in-tangent a_{k+1} of key k+1, both scaled by the key interval.
        const double s2 = s * s, s3 = s2 * s;
        const double *bk = out_tangent(k), *ak1 = in_tangent(k + 1);
        for (size_t j = 0; j < w; ++j)
          v[j] = (2 * s3 - 3 * s2 + 1) * a[j] + td * (s3 - 2 * s2 + s) * bk[j] + (-2 * s3 + 3 * s2) * b[j] + td * (s3 - s2) * ak1[j];
        break;
      }
    }
  }
  if (c.path == AnimatedPath::Rotation) {
    const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
    if (len > 0.0) {
      for (double& x : v) x /= len;  // "normalised after cubic" (Appendix C)
    } else {
      v = {0.0, 0.0, 0.0, 1.0};
    }
  }
  return v;
}

NodePose pose_nodes(const SceneSource& src, int animation, double t) {
  std::vector<glm::dvec3> translation(src.nodes.size()), scale(src.nodes.size());
  std::vector<glm::dquat> rotation(src.nodes.size());
  NodePose out;
  out.weights.resize(src.nodes.size());
  for (size_t i = 0; i < src.nodes.size(); ++i) {
    translation[i] = src.nodes[i].translation, rotation[i] = src.nodes[i].rotation, scale[i] = src.nodes[i].scale;
    out.weights[i] = src.nodes[i].weights;
  }
  if (animation >= 0 && size_t(animation) < src.animations.size()) {
    for (const auto& c : src.animations[size_t(animation)].channels) {
      const std::vector<double> v = evaluate(c, t);
      switch (c.path) {
        case AnimatedPath::Translation: translation[size_t(c.node)] = glm::dvec3(v[0], v[1], v[2]); break;
        case AnimatedPath::Rotation: rotation[size_t(c.node)] = glm::dquat(v[3], v[0], v[1], v[2]); break;
        case AnimatedPath::Scale: scale[size_t(c.node)] = glm::dvec3(v[0], v[1], v[2]); break;
        case AnimatedPath::Weights: out.weights[size_t(c.node)] = v; break;
      }
    }
  }
  out.world.assign(src.nodes.size(), glm::dmat4(1.0));
  // Parents before children: the hierarchy was checked to be a forest, so a stack walk from
  // its roots reaches every node exactly once. Every root, not only the displayed scene's:
  // a skin's joints may hang outside it.
  std::vector<int> stack;
  for (size_t i = src.nodes.size(); i-- > 0;)
    if (src.nodes[i].parent < 0) stack.push_back(int(i));
  while (!stack.empty()) {
    const int i = stack.back();
    stack.pop_back();
    const NodeSource& n = src.nodes[size_t(i)];
    // glTF 2.0 spec, 3.5.3 "Transformations": local = T * R * S, or the matrix when given.
    const glm::dmat4 local = n.has_matrix ? n.matrix
                                          : glm::translate(glm::dmat4(1.0), translation[size_t(i)]) * glm::mat4_cast(rotation[size_t(i)]) *
                                                glm::scale(glm::dmat4(1.0), scale[size_t(i)]);
    out.world[size_t(i)] = n.parent >= 0 ? out.world[size_t(n.parent)] * local : local;
    for (auto it = n.children.rbegin(); it != n.children.rend(); ++it) stack.push_back(*it);
  }
  return out;
}

}  // namespace giq::scenes
