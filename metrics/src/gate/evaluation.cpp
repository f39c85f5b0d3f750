#include "giq/gate/evaluation.h"

#include <algorithm>
#include <cctype>
#include <cstdio>

#include "giq/gate/metric_lookup.h"

namespace giq::gate {
namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool beyond(const Bound& b, double value, double level) {
  return b.better == Better::Lower ? value > level : value < level;
}

}  // namespace

const char* to_string(Status s) {
  switch (s) {
    case Status::Pass:
      return "PASS";
    case Status::Warn:
      return "WARN";
    case Status::Fail:
      return "FAIL";
    case Status::Unresolved:
      return "UNRESOLVED";
    case Status::Skip:
      return "SKIP";
  }
  return "?";
}

std::string describe(const Bound& b) {
  const char* op = b.better == Better::Lower ? "<= " : ">= ";
  std::string s;
  if (b.fail) s = op + num(*b.fail);
  if (b.warn)
    s += s.empty() ? std::string("warn ") + op + num(*b.warn) : " (warn " + num(*b.warn) + ")";
  if (!b.device.empty()) s += " on '" + b.device + "'";
  return s;
}

std::vector<Outcome> evaluate(const Case& c, const Evidence& ev) {
  std::vector<Outcome> out;
  const FrameTime ft = ev.timings ? frame_time(*ev.timings) : FrameTime{};
  for (const Bound& b : c.bounds) {
    Outcome o;
    o.case_name = c.name;
    o.metric = b.metric;
    o.bound = describe(b);
    auto fail = [&](const std::string& why) {
      o.status = Status::Fail;
      o.fails_gate = true;
      o.message = why;
      out.push_back(o);
    };
    if (!ev.problem.empty()) {
      o.error = true;
      fail(ev.problem);
      continue;
    }
    if (!b.device.empty()) {
      if (!ev.timings) {
        fail("the bound is for device '" + b.device +
             "' but there is no timings.json naming the device");
        continue;
      }
      if (lower(ft.device).find(lower(b.device)) == std::string::npos) {
        o.status = Status::Skip;
        o.message = "bound is for device '" + b.device + "'; this run used '" + ft.device + "'";
        if (b.metric == "gpu_ms" && ft.gpu_ms) o.value = ft.gpu_ms;
        out.push_back(o);
        continue;
      }
    }
    MetricValue m;
    if (b.metric == "gpu_ms") {
      if (!ft.gpu_ms) {
        fail("timings.json has no frame_gpu_ms.median");
        continue;
      }
      m.value = ft.gpu_ms;
      m.path = "timings.json frame_gpu_ms.median";
    } else {
      if (!ev.metrics) {
        fail("no metrics.json for this case");
        continue;
      }
      const auto found = find_metric(*ev.metrics, b.metric);
      if (!found) {
        fail("metrics.json has no metric '" + b.metric +
             "' (looked under metrics, sequence and last_frame.metrics; see docs/metrics.md)");
        continue;
      }
      m = *found;
      if (!m.value) {
        fail("the metric is undefined for this case" +
             (m.note.empty() ? std::string() : ": " + m.note));
        continue;
      }
    }
    o.value = m.value;
    const double v = *m.value;
    const bool over_fail = b.fail && beyond(b, v, *b.fail);
    const bool over_warn = b.warn && beyond(b, v, *b.warn);
    if (m.unresolved) {
      o.status = Status::Unresolved;
      if (over_fail) {
        o.fails_gate = true;
        o.message =
            "beyond the fail level, but below the golden's noise resolution: the golden's noise "
            "may account "
            "for it; render the golden with more samples (giq golden update)";
      } else {
        o.message = std::string(over_warn ? "beyond the warn level and " : "") +
                    "within the bound, but below the golden's noise resolution: the golden cannot "
                    "measure an error "
                    "this small";
      }
    } else if (over_fail) {
      o.status = Status::Fail;
      o.fails_gate = true;
      o.message = b.metric + " = " + num(v) + " is beyond the fail level " + num(*b.fail);
    } else if (over_warn) {
      o.status = Status::Warn;
      o.message = b.metric + " = " + num(v) + " is beyond the warn level " + num(*b.warn);
    } else {
      o.status = Status::Pass;
    }
    out.push_back(o);
  }
  return out;
}

int exit_code(const std::vector<Outcome>& outcomes) {
  return std::any_of(outcomes.begin(), outcomes.end(),
                     [](const Outcome& o) { return o.fails_gate; })
             ? 1
             : 0;
}

}  // namespace giq::gate
