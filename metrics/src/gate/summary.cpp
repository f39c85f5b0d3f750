#include "giq/gate/summary.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace giq::gate {
namespace {

std::string value_text(const Outcome& o) {
  if (!o.value) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", *o.value);
  return buf;
}

// Markdown table cells: a '|' would end the cell, a newline the row.
std::string md_cell(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '|')
      out += "\\|";
    else if (c == '\n' || c == '\r')
      out += ' ';
    else if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else
      out += c;
  }
  return out;
}

int rank(const Outcome& o) {
  if (o.fails_gate) return 0;
  switch (o.status) {
    case Status::Unresolved:
      return 1;
    case Status::Warn:
      return 2;
    case Status::Skip:
      return 3;
    default:
      return 4;
  }
}

}  // namespace

std::string count_line(const std::vector<Outcome>& outcomes) {
  int n[5] = {0, 0, 0, 0, 0};
  for (const Outcome& o : outcomes) ++n[int(o.status)];
  std::ostringstream s;
  s << outcomes.size() << " checks: " << n[int(Status::Pass)] << " PASS, " << n[int(Status::Warn)]
    << " WARN, " << n[int(Status::Fail)] << " FAIL, " << n[int(Status::Unresolved)]
    << " UNRESOLVED, " << n[int(Status::Skip)] << " SKIP";
  return s.str();
}

std::string format_table(const std::vector<Outcome>& outcomes) {
  size_t wc = 4, wm = 6, wv = 5, wb = 5;
  for (const Outcome& o : outcomes) {
    wc = std::max(wc, o.case_name.size());
    wm = std::max(wm, o.metric.size());
    wv = std::max(wv, value_text(o).size());
    wb = std::max(wb, o.bound.size());
  }
  std::ostringstream s;
  auto line = [&](const std::string& c, const std::string& m, const std::string& v,
                  const std::string& b, const std::string& st, const std::string& msg) {
    char buf[1024];
    std::snprintf(buf, sizeof buf, "%-*s  %-*s  %*s  %-*s  %-10s", int(wc), c.c_str(), int(wm),
                  m.c_str(), int(wv), v.c_str(), int(wb), b.c_str(), st.c_str());
    s << buf;
    if (!msg.empty()) s << "  " << msg;
    s << '\n';
  };
  line("case", "metric", "value", "bound", "status", "");
  for (const Outcome& o : outcomes)
    line(o.case_name, o.metric, value_text(o), o.bound, to_string(o.status),
         o.status == Status::Pass ? "" : o.message);
  return s.str();
}

std::string markdown_summary(const std::vector<Outcome>& outcomes) {
  std::vector<const Outcome*> sorted;
  for (const Outcome& o : outcomes) sorted.push_back(&o);
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const Outcome* a, const Outcome* b) { return rank(*a) < rank(*b); });
  const bool failed = exit_code(outcomes) != 0;
  std::ostringstream s;
  s << "# giq gate: " << (failed ? "FAILED" : "passed") << "\n\n" << count_line(outcomes) << "\n\n";
  s << "| case | metric | value | bound | status | note |\n|---|---|---:|---|---|---|\n";
  for (const Outcome* o : sorted)
    s << "| " << md_cell(o->case_name) << " | " << md_cell(o->metric) << " | " << value_text(*o)
      << " | " << md_cell(o->bound) << " | " << (o->fails_gate ? "**" : "") << to_string(o->status)
      << (o->fails_gate ? "**" : "") << " | " << md_cell(o->message) << " |\n";
  return s.str();
}

}  // namespace giq::gate
