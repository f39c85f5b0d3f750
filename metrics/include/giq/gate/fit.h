#pragma once
// Power-law fit for convergence plots: error ~ a * x^slope, fitted by ordinary least squares
// on (log10 x, log10 error). A Monte Carlo estimator's RMSE falls as spp^-1/2, its MSE as
// spp^-1 (Veach 1997, section 2.4), so the fitted slope checks the reference renderer
// converges as it should.

#include <cstddef>
#include <vector>

namespace giq::gate {

struct LineFit {
  double slope = 0.0;
  double intercept = 0.0;  // log10 a
  double r2 = 0.0;         // coefficient of determination on the logs
  size_t points = 0;       // points used (positive and finite x and y)
};

// Throws std::invalid_argument when fewer than two usable points or all x are equal.
LineFit fit_log_log(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace giq::gate
