#pragma once
// Evaluating a gate case: each bound against the case's metrics.json (and timings.json for
// gpu_ms) gives one outcome, PASS, WARN, FAIL, UNRESOLVED or SKIP.
//
// Noise: a path-traced golden has noise, and noise only makes a technique look worse (it adds
// its variance to every squared error and its grain to every perceptual difference), so the
// measured value is a conservative estimate of the true error. A metric that `giq score`
// flags `unresolved` (too close to the golden's noise floor to be measured) is therefore
// reported UNRESOLVED, never PASS: when the measured value still satisfies the bound, the bound
// holds and the gate does not fail; when it does not, the gate cannot tell the technique's error
// from the golden's noise, and it fails, asking for a less noisy golden.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "giq/gate/config.h"

namespace giq::gate {

enum class Status { Pass, Warn, Fail, Unresolved, Skip };
const char* to_string(Status s);

struct Outcome {
  std::string case_name;
  std::string metric;
  Status status = Status::Fail;
  std::optional<double> value;
  std::string bound;    // e.g. "<= 0.08 (warn 0.05)"
  std::string message;  // why, for anything but a plain PASS
  bool fails_gate = false;
  // The case could not be rendered or scored (a crash, a missing file, a stale golden): no
  // verdict on the technique, reported as an error rather than a failure (JUnit <error>).
  bool error = false;
};

// What the gate has for one case. `problem` says why there is nothing to evaluate (a render
// crashed, a golden is stale or missing, a file is missing); every bound then fails with it.
struct Evidence {
  std::optional<nlohmann::json> metrics;
  std::optional<nlohmann::json> timings;
  std::string problem;
};

std::vector<Outcome> evaluate(const Case& c, const Evidence& evidence);

// "<= 0.08 (warn 0.05)", ">= 0.9", "<= 4 ms on 'H100'".
std::string describe(const Bound& b);

// 0 when nothing fails the gate (PASS, WARN, SKIP, resolved-within-bound UNRESOLVED), else 1.
int exit_code(const std::vector<Outcome>& outcomes);

}  // namespace giq::gate
