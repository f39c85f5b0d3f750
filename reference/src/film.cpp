#include "giq/reference/film.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace giq::reference {
namespace {

// Splits the beauty b into direct d and indirect r with d + r == b exactly in float
// arithmetic (0 <= d <= b on entry). r starts as the rounded difference and moves by one ulp
// while the rounded sum misses. When d has finer ulps than b, every candidate sum can land
// exactly halfway between floats and round (to even) away from b; moving d by one of its
// ulps (a relative change of 6e-8) shifts the sums off the tie.
void split_beauty(float b, float& d, float& r) {
  for (int attempt = 0; attempt < 4; ++attempt) {
    r = b - d;
    for (int i = 0; i < 4 && d + r != b; ++i) r = std::nextafter(r, d + r < b ? INFINITY : -INFINITY);
    if (d + r == b && r >= 0.0f) return;
    d = std::nextafter(d, 0.0f);
  }
}

double luminance(const double c[3]) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

// E[s] / sigma for a sample standard deviation s with k degrees of freedom of normal data:
// c4 = sqrt(2 / k) Gamma((k + 1) / 2) / Gamma(k / 2) (ASTM E2587; 0.80 at k = 1, 0.97 at
// k = 7, 1 in the limit). The square root of an unbiased variance underestimates sigma by this
// factor, which matters for a few blocks' worth of degrees of freedom.
double c4(uint32_t k) {
  if (k == 0) return 1.0;
  const double n = double(k);
  return std::sqrt(2.0 / n) * std::exp(std::lgamma(0.5 * (n + 1.0)) - std::lgamma(0.5 * n));
}

}  // namespace

uint32_t Film::min_samples() const {
  uint32_t n = std::numeric_limits<uint32_t>::max();
  for (const PixelAccumulator& p : pixels) n = std::min(n, p.samples);
  return pixels.empty() ? 0 : n;
}

uint64_t Film::nonfinite_samples() const {
  uint64_t n = 0;
  for (const PixelAccumulator& p : pixels) n += p.nonfinite;
  return n;
}

double Film::relative_standard_error() const {
  double image_mean = 0.0;
  for (const PixelAccumulator& p : pixels) image_mean += luminance(p.mean);
  image_mean /= std::max<size_t>(1, pixels.size());
  if (!(image_mean > 0.0)) return 0.0;
  double sum = 0.0;
  size_t count = 0;
  for (const PixelAccumulator& p : pixels) {
    const double y = luminance(p.mean);
    if (y < 1e-3 * image_mean) continue;
    // Variance of the luminance of the mean, ignoring the (positive) covariance between
    // channels, which only makes the estimate more conservative when added: bound it by
    // (sum_c w_c sigma_c)^2 instead.
    double s = 0.0;
    const double w[3] = {0.2126, 0.7152, 0.0722};
    for (int c = 0; c < 3; ++c) s += w[c] * std::sqrt(p.variance_of_mean(c));
    sum += s / (c4(p.variance_dof()) * y);
    ++count;
  }
  return count == 0 ? 0.0 : sum / double(count);
}

image::Image Film::to_image() const {
  image::Image img(width, height);
  float* rgb[3] = {img.add_channel("R"), img.add_channel("G"), img.add_channel("B")};
  float* direct[3] = {img.add_channel("direct.R"), img.add_channel("direct.G"), img.add_channel("direct.B")};
  float* indirect[3] = {img.add_channel("indirect.R"), img.add_channel("indirect.G"), img.add_channel("indirect.B")};
  float* albedo[3] = {img.add_channel("albedo.R"), img.add_channel("albedo.G"), img.add_channel("albedo.B")};
  float* normal[3] = {img.add_channel("N.X"), img.add_channel("N.Y"), img.add_channel("N.Z")};
  float* z = img.add_channel("Z");
  float* id = img.add_channel("objectId");
  float* var[3] = {img.add_channel("variance.R"), img.add_channel("variance.G"), img.add_channel("variance.B")};
  float* spp = img.add_channel("spp");
  for (size_t i = 0; i < pixels.size(); ++i) {
    const PixelAccumulator& p = pixels[i];
    const PixelAux& a = aux[i];
    const double n = std::max(1.0, double(p.samples));
    for (int c = 0; c < 3; ++c) {
      rgb[c][i] = float(p.mean[c]);
      // The direct sum can exceed n * mean by rounding alone; clamp so indirect >= 0.
      const float b = rgb[c][i];
      float d = std::min(float(p.direct_sum[c] / n), b), r = 0.0f;
      split_beauty(b, d, r);
      direct[c][i] = d;
      indirect[c][i] = r;
      albedo[c][i] = a.albedo[c];
      normal[c][i] = a.normal[c];
      var[c][i] = float(p.variance_of_mean(c));
    }
    z[i] = a.depth;
    id[i] = float(a.object_id);
    spp[i] = float(p.samples);
  }
  return img;
}

}  // namespace giq::reference
