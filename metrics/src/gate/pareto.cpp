#include "giq/gate/pareto.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace giq::gate {

std::vector<bool> pareto_front(const std::vector<CostError>& p) {
  std::vector<bool> on(p.size(), false);
  std::vector<size_t> idx;
  for (size_t i = 0; i < p.size(); ++i)
    if (std::isfinite(p[i].cost) && std::isfinite(p[i].error)) idx.push_back(i);
  std::sort(idx.begin(), idx.end(), [&](size_t a, size_t b) {
    return p[a].cost != p[b].cost ? p[a].cost < p[b].cost : p[a].error < p[b].error;
  });
  // Walking in cost order, a point is dominated exactly when an earlier point (cheaper or as
  // cheap) has a strictly smaller error, or has the same error at a strictly smaller cost.
  double best = std::numeric_limits<double>::infinity();
  double best_cost = std::numeric_limits<double>::infinity();
  for (size_t i : idx) {
    const bool dominated = best < p[i].error || (best == p[i].error && best_cost < p[i].cost);
    on[i] = !dominated;
    if (p[i].error < best) best = p[i].error, best_cost = p[i].cost;
  }
  return on;
}

}  // namespace giq::gate
