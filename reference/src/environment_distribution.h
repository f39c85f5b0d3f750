#pragma once
// Importance sampling of an equirectangular environment map (scenes/environment.h): a
// piecewise-constant 2D distribution over its texels, each weighted by its luminance times
// sin(theta) at its row's centre, sampled by inverting the marginal (rows) and conditional
// (columns) CDFs (pbrt-v4, "Piecewise-Constant 2D Distributions" and "Image Infinite
// Lights"). The pdf over the image square becomes one over solid angle by the mapping's
// Jacobian: pdf(w) = pdf(u, v) / (2 pi^2 sin(theta)).

#include <glm/glm.hpp>

#include <vector>

#include "giq/scenes/texture.h"

namespace giq::reference {

class EnvironmentDistribution {
 public:
  EnvironmentDistribution() = default;
  explicit EnvironmentDistribution(const scenes::Texture& map);

  bool empty() const { return width_ == 0; }
  // A direction for the numbers u in [0, 1)^2, with its solid-angle pdf (0: none).
  glm::vec3 sample(glm::vec2 u, float& pdf) const;
  // The solid-angle pdf of sampling unit direction w.
  float pdf(glm::vec3 w) const;

 private:
  int width_ = 0, height_ = 0;
  std::vector<float> func_;                     // width x height weights
  std::vector<float> conditional_cdf_;          // per row, width + 1 entries
  std::vector<float> row_integral_;             // per row: sum of its weights / width
  std::vector<float> marginal_cdf_;             // height + 1 entries
  float integral_ = 0.0f;                       // over the unit square
};

}  // namespace giq::reference
