#include "giq/gate/fit.h"

#include <cmath>
#include <stdexcept>

namespace giq::gate {

LineFit fit_log_log(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size()) throw std::invalid_argument("fit_log_log: x and y differ in length");
  std::vector<double> lx, ly;
  for (size_t i = 0; i < x.size(); ++i)
    if (x[i] > 0.0 && y[i] > 0.0 && std::isfinite(x[i]) && std::isfinite(y[i]))
      lx.push_back(std::log10(x[i])), ly.push_back(std::log10(y[i]));
  const size_t n = lx.size();
  if (n < 2) throw std::invalid_argument("fit_log_log: fewer than two positive points");
  double mx = 0.0, my = 0.0;
  for (size_t i = 0; i < n; ++i) mx += lx[i], my += ly[i];
  mx /= double(n), my /= double(n);
  // Centred sums keep the normal equations well conditioned.
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double dx = lx[i] - mx, dy = ly[i] - my;
    sxx += dx * dx, sxy += dx * dy, syy += dy * dy;
  }
  if (sxx <= 0.0) throw std::invalid_argument("fit_log_log: every x is the same");
  LineFit f;
  f.points = n;
  f.slope = sxy / sxx;
  f.intercept = my - f.slope * mx;
  f.r2 = syy > 0.0 ? (sxy * sxy) / (sxx * syy) : 1.0;
  return f;
}

}  // namespace giq::gate
