#include "filters.h"

#include <cmath>
#include <numbers>

#include "constants.h"

namespace giq::metrics::flip {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// exp(-pi^2 x^2 / b): the spatial shape of the frequency-domain Gaussian exp(-b f^2), x in degrees.
float csf_shape(float x_degrees, float b) { return std::exp(-kPi * kPi * x_degrees * x_degrees / b); }

// [FLIP] the spatial-domain amplitude of a CSF term a exp(-b f^2) is a sqrt(pi / b).
double csf_amplitude(float a, float b) { return double(a) * std::sqrt(double(kPi) / double(b)); }

// A single-Gaussian channel: the 2D kernel is w(x)w(y) with w normalised to sum to 1.
std::vector<float> single_gaussian_taps(int radius, float pixels_per_degree, float b) {
  std::vector<float> w(size_t(2 * radius + 1));
  double sum = 0.0;
  for (int k = -radius; k <= radius; ++k) {
    w[size_t(k + radius)] = csf_shape(float(k) / pixels_per_degree, b);
    sum += w[size_t(k + radius)];
  }
  for (float& v : w) v = float(v / sum);
  return w;
}

}  // namespace

// [FLIP]: the filter spans 3 standard deviations of the widest spatial Gaussian; the spatial
// standard deviation of exp(-pi^2 x^2 / b) is sqrt(b / (2 pi^2)) degrees.
static int csf_radius(float pixels_per_degree) {
  return int(std::ceil(kCsfRadiusInStdDevs * std::sqrt(kCsfWidestB / (2.0f * kPi * kPi)) * pixels_per_degree));
}

CsfFilters make_csf_filters(float pixels_per_degree) {
  CsfFilters f;
  f.radius = csf_radius(pixels_per_degree);
  // Y and Cx: a2 = 0, so the amplitude cancels in the normalisation.
  f.y = single_gaussian_taps(f.radius, pixels_per_degree, kCsfAchromatic.b1);
  f.cx = single_gaussian_taps(f.radius, pixels_per_degree, kCsfRedGreen.b1);
  // Cz: 2D kernel c1 g1(x)g1(y) + c2 g2(x)g2(y) with c_i = a_i sqrt(pi/b_i), normalised by its
  // 2D sum N = c1 S1^2 + c2 S2^2 (S_i = sum of g_i); each term splits into sqrt(c_i/N) g_i per axis.
  const size_t n = size_t(2 * f.radius + 1);
  std::vector<double> g1(n), g2(n);
  double s1 = 0.0, s2 = 0.0;
  for (int k = -f.radius; k <= f.radius; ++k) {
    const float x = float(k) / pixels_per_degree;
    g1[size_t(k + f.radius)] = csf_shape(x, kCsfBlueYellow.b1);
    g2[size_t(k + f.radius)] = csf_shape(x, kCsfBlueYellow.b2);
    s1 += g1[size_t(k + f.radius)];
    s2 += g2[size_t(k + f.radius)];
  }
  const double c1 = csf_amplitude(kCsfBlueYellow.a1, kCsfBlueYellow.b1);
  const double c2 = csf_amplitude(kCsfBlueYellow.a2, kCsfBlueYellow.b2);
  const double norm = c1 * s1 * s1 + c2 * s2 * s2;
  const double k1 = std::sqrt(c1 / norm), k2 = std::sqrt(c2 / norm);
  f.cz1.resize(n);
  f.cz2.resize(n);
  for (size_t i = 0; i < n; ++i) {
    f.cz1[i] = float(k1 * g1[i]);
    f.cz2[i] = float(k2 * g2[i]);
  }
  return f;
}

FeatureFilters make_feature_filters(float pixels_per_degree) {
  const float sigma = 0.5f * kFeatureWidthDegrees * pixels_per_degree;
  FeatureFilters f;
  f.radius = int(std::ceil(kFeatureRadiusInStdDevs * sigma));
  const size_t n = size_t(2 * f.radius + 1);
  f.gaussian.resize(n);
  f.first.resize(n);
  f.second.resize(n);
  double g_sum = 0.0, d1_pos = 0.0, d1_neg = 0.0, d2_pos = 0.0, d2_neg = 0.0;
  for (int k = -f.radius; k <= f.radius; ++k) {
    const float x = float(k);
    const float g = std::exp(-(x * x) / (2.0f * sigma * sigma));
    // Derivatives of the Gaussian up to positive factors, which the normalisation removes:
    // g' ~ -x g, g'' ~ (x^2 / sigma^2 - 1) g.
    const float d1 = -x * g;
    const float d2 = (x * x / (sigma * sigma) - 1.0f) * g;
    const size_t i = size_t(k + f.radius);
    f.gaussian[i] = g;
    f.first[i] = d1;
    f.second[i] = d2;
    g_sum += g;
    (d1 > 0.0f ? d1_pos : d1_neg) += std::fabs(d1);
    (d2 > 0.0f ? d2_pos : d2_neg) += std::fabs(d2);
  }
  // A degenerate filter (pixels per degree so small that the radius is 0) has no derivative
  // taps; its derivatives stay 0 rather than dividing by a zero sum.
  auto scale = [](float v, double pos, double neg) {
    const double s = v > 0.0f ? pos : neg;
    return s > 0.0 ? float(v / s) : 0.0f;
  };
  for (size_t i = 0; i < n; ++i) {
    f.gaussian[i] = float(f.gaussian[i] / g_sum);
    f.first[i] = scale(f.first[i], d1_pos, d1_neg);
    f.second[i] = scale(f.second[i], d2_pos, d2_neg);
  }
  return f;
}

}  // namespace giq::metrics::flip
