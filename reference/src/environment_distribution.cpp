#include "environment_distribution.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "giq/scenes/environment.h"
#include "giq/scenes/light.h"

namespace giq::reference {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// Fills cdf (n + 1 entries) for the n weights f (their mean is returned); an all-zero row gets
// a uniform CDF so that sampling stays defined (its pdf is 0 anyway).
float build_cdf(const float* f, int n, float* cdf) {
  double sum = 0.0;
  cdf[0] = 0.0f;
  for (int i = 0; i < n; ++i) sum += double(f[i]), cdf[i + 1] = float(sum);
  if (sum > 0.0)
    for (int i = 1; i <= n; ++i) cdf[i] = float(double(cdf[i]) / sum);
  else
    for (int i = 1; i <= n; ++i) cdf[i] = float(i) / float(n);
  cdf[n] = 1.0f;
  return float(sum / n);
}

// u's continuous position in [0, n) in a CDF of n bins; `bin` (if given) gets its bin.
float sample_continuous(const float* cdf, int n, float u, int* bin_out = nullptr) {
  const float* it = std::upper_bound(cdf, cdf + n + 1, u);
  const int bin = std::clamp(int(it - cdf) - 1, 0, n - 1);
  if (bin_out) *bin_out = bin;
  const float width = cdf[bin + 1] - cdf[bin];
  const float t = width > 0.0f ? std::clamp((u - cdf[bin]) / width, 0.0f, 1.0f) : 0.5f;
  return std::min(float(bin) + t, std::nextafter(float(n), 0.0f));
}

}  // namespace

EnvironmentDistribution::EnvironmentDistribution(const scenes::Texture& map)
    : width_(map.width), height_(map.height) {
  func_.resize(size_t(width_) * size_t(height_));
  for (int y = 0; y < height_; ++y) {
    const float s = std::sin(kPi * (float(y) + 0.5f) / float(height_));
    for (int x = 0; x < width_; ++x) func_[size_t(y) * size_t(width_) + size_t(x)] = float(scenes::luminance(glm::vec3(map.texel(x, y)))) * s;
  }
  conditional_cdf_.resize(size_t(height_) * size_t(width_ + 1));
  row_integral_.resize(size_t(height_));
  for (int y = 0; y < height_; ++y)
    row_integral_[size_t(y)] = build_cdf(&func_[size_t(y) * size_t(width_)], width_, &conditional_cdf_[size_t(y) * size_t(width_ + 1)]);
  marginal_cdf_.resize(size_t(height_ + 1));
  integral_ = build_cdf(row_integral_.data(), height_, marginal_cdf_.data());
}

glm::vec3 EnvironmentDistribution::sample(glm::vec2 u, float& pdf) const {
  int row = 0;
  const float v = sample_continuous(marginal_cdf_.data(), height_, u.y, &row) / float(height_);
  const float x = sample_continuous(&conditional_cdf_[size_t(row) * size_t(width_ + 1)], width_, u.x) / float(width_);
  const glm::vec3 w = scenes::equirect_direction({x, v});
  // The pdf of the direction as pdf() and the radiance lookup see it (the texel of w's own
  // coordinates, which rounding can move across a texel edge from the sampled one).
  pdf = this->pdf(w);
  return w;
}

float EnvironmentDistribution::pdf(glm::vec3 w) const {
  if (integral_ <= 0.0f) return 0.0f;
  const glm::vec2 uv = scenes::equirect_uv(w);
  const int x = std::clamp(int(std::floor((uv.x - std::floor(uv.x)) * float(width_))), 0, width_ - 1);
  const int y = std::clamp(int(std::floor(uv.y * float(height_))), 0, height_ - 1);
  // sin(theta) from the horizontal components, which keep their precision near the poles
  // (1 - y^2 rounds to 0 within 3e-4 rad of them); exactly at a pole the density is infinite
  // and its measure zero: a tiny floor keeps it finite.
  const float s = std::max(std::sqrt(w.x * w.x + w.z * w.z), 1e-20f);
  return func_[size_t(y) * size_t(width_) + size_t(x)] / integral_ / (2.0f * kPi * kPi * s);
}

}  // namespace giq::reference
