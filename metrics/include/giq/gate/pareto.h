#pragma once
// The speed/accuracy Pareto front: a setting is on the front when no other setting is both at
// least as fast and at least as accurate, and strictly better in one of the two.

#include <vector>

namespace giq::gate {

struct CostError {
  double cost;   // GPU ms per frame
  double error;  // any error metric, lower is better
};

// on_front[i] for each point. Points with a non-finite cost or error are never on the front
// and never dominate. Equal points are all on the front (neither is strictly better).
// O(n log n): sort by cost, then error, and keep the running minimum error.
std::vector<bool> pareto_front(const std::vector<CostError>& points);

}  // namespace giq::gate
