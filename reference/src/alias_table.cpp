#include "giq/reference/alias_table.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace giq::reference {

AliasTable::AliasTable(std::span<const double> weights) {
  double sum = 0.0;
  for (double w : weights) {
    if (!std::isfinite(w) || w < 0.0) throw std::invalid_argument("alias table weights must be finite and >= 0");
    sum += w;
  }
  if (!(sum > 0.0)) throw std::invalid_argument("alias table needs a positive total weight");
  const size_t n = weights.size();
  pmf_.resize(n);
  bins_.resize(n);
  // Scaled probabilities p_i * n: bins below 1 ("small") are topped up by one entry above 1.
  std::vector<double> scaled(n);
  std::vector<uint32_t> small, large;
  for (size_t i = 0; i < n; ++i) {
    pmf_[i] = float(weights[i] / sum);
    scaled[i] = weights[i] / sum * double(n);
    (scaled[i] < 1.0 ? small : large).push_back(uint32_t(i));
  }
  while (!small.empty() && !large.empty()) {
    const uint32_t s = small.back(), l = large.back();
    small.pop_back();
    bins_[s] = {float(scaled[s]), l};
    scaled[l] -= 1.0 - scaled[s];
    if (scaled[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // What remains is 1 up to rounding (Vose, section 4): those bins keep their own entry.
  for (uint32_t i : small) bins_[i] = {1.0f, i};
  for (uint32_t i : large) bins_[i] = {1.0f, i};
}

}  // namespace giq::reference
