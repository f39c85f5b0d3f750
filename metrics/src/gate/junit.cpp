#include "giq/gate/junit.h"

#include <cstdio>
#include <map>
#include <sstream>

#include "giq/gate/escape.h"

namespace giq::gate {
namespace {

std::string seconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", s);
  return buf;
}

std::string value_text(const Outcome& o) {
  if (!o.value) return "none";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", *o.value);
  return buf;
}

struct Counts {
  int tests = 0, failures = 0, errors = 0, skipped = 0;
  void add(const Outcome& o) {
    ++tests;
    if (o.error)
      ++errors;
    else if (o.fails_gate)
      ++failures;
    else if (o.status == Status::Skip || o.status == Status::Unresolved)
      ++skipped;
  }
  std::string attributes() const {
    return "tests=\"" + std::to_string(tests) + "\" failures=\"" + std::to_string(failures) +
           "\" errors=\"" + std::to_string(errors) + "\" skipped=\"" + std::to_string(skipped) + "\"";
  }
};

}  // namespace

std::string junit_xml(const std::vector<Outcome>& outcomes,
                      const std::vector<std::pair<std::string, double>>& seconds_per_case) {
  // Cases in first-seen order.
  std::vector<std::string> order;
  std::map<std::string, std::vector<const Outcome*>> by_case;
  for (const Outcome& o : outcomes) {
    if (!by_case.count(o.case_name)) order.push_back(o.case_name);
    by_case[o.case_name].push_back(&o);
  }
  std::map<std::string, double> time;
  for (const auto& [name, s] : seconds_per_case) time[name] = s;

  Counts total;
  double total_time = 0.0;
  for (const Outcome& o : outcomes) total.add(o);
  for (const auto& name : order) total_time += time.count(name) ? time[name] : 0.0;

  std::ostringstream x;
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  x << "<testsuites name=\"giq gate\" " << total.attributes() << " time=\"" << seconds(total_time)
    << "\">\n";
  for (const auto& name : order) {
    Counts c;
    for (const Outcome* o : by_case[name]) c.add(*o);
    const double t = time.count(name) ? time[name] : 0.0;
    x << "  <testsuite name=\"" << xml_escape(name) << "\" " << c.attributes() << " time=\""
      << seconds(t) << "\">\n";
    // The case's wall time (rendering and scoring serve all its bounds) shared among them,
    // so that the testcases add up to the suite.
    const double each = by_case[name].empty() ? 0.0 : t / double(by_case[name].size());
    for (const Outcome* o : by_case[name]) {
      x << "    <testcase classname=\"giq.gate." << xml_escape(name) << "\" name=\""
        << xml_escape(o->metric) << "\" time=\"" << seconds(each) << "\">\n";
      const std::string detail =
          o->error ? "ERROR: the case could not be rendered or scored, so " + o->metric + " (bound " + o->bound +
                         ") has no value: " + o->message
                   : std::string(to_string(o->status)) + ": " + o->metric + " = " + value_text(*o) + ", bound " +
                         o->bound + (o->message.empty() ? "" : "; " + o->message);
      if (o->error) {
        x << "      <error message=\"" << xml_escape(detail) << "\" type=\"ERROR\">" << xml_escape(detail)
          << "</error>\n";
      } else if (o->fails_gate) {
        x << "      <failure message=\"" << xml_escape(detail) << "\" type=\""
          << to_string(o->status) << "\">" << xml_escape(detail) << "</failure>\n";
      } else if (o->status == Status::Skip || o->status == Status::Unresolved) {
        x << "      <skipped message=\"" << xml_escape(detail) << "\"/>\n";
      } else {
        x << "      <system-out>" << xml_escape(detail) << "</system-out>\n";
      }
      x << "    </testcase>\n";
    }
    x << "  </testsuite>\n";
  }
  x << "</testsuites>\n";
  return x.str();
}

}  // namespace giq::gate
