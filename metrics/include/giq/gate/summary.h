#pragma once
// The human outputs of `giq gate`: a fixed-width table for the terminal and gate-summary.md
// (counts, then every outcome, failures first) for CI job summaries and merge requests.

#include <string>
#include <vector>

#include "giq/gate/evaluation.h"

namespace giq::gate {

std::string format_table(const std::vector<Outcome>& outcomes);
std::string markdown_summary(const std::vector<Outcome>& outcomes);
// "12 checks: 9 PASS, 1 WARN, 1 FAIL, 0 UNRESOLVED, 1 SKIP"
std::string count_line(const std::vector<Outcome>& outcomes);

}  // namespace giq::gate
