#include "giq/reference/film.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace giq::reference {
namespace {

double luminance(const double c[3]) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

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
    sum += s / y;
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
      direct[c][i] = std::min(float(p.direct_sum[c] / n), rgb[c][i]);
      indirect[c][i] = rgb[c][i] - direct[c][i];
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
