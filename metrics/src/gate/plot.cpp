#include "giq/gate/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "giq/gate/escape.h"

namespace giq::gate {
namespace {

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

std::string px(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

bool usable(double v, bool log) {
  return std::isfinite(v) && (!log || v > 0.0);
}

// One axis: data range -> pixels, in log10 space when `log`.
struct Axis {
  bool log = false;
  double lo = 0.0, hi = 1.0;  // in transformed space
  double p0 = 0.0, p1 = 1.0;  // pixels

  double t(double v) const { return log ? std::log10(v) : v; }
  double map(double v) const { return p0 + (t(v) - lo) / (hi - lo) * (p1 - p0); }

  void fit(double mn, double mx) {
    lo = t(mn), hi = t(mx);
    if (hi - lo < 1e-12) {
      const double pad = log ? 0.5 : std::max(std::abs(lo) * 0.1, 1e-6);
      lo -= pad, hi += pad;
    }
    if (log) {
      // Whole decades, with a margin so a point on a decade is not drawn on the frame.
      lo = std::floor(lo - 0.05), hi = std::ceil(hi + 0.05);
      if (hi == lo) hi += 1.0;
    } else {
      const double pad = (hi - lo) * 0.06;
      lo -= pad, hi += pad;
    }
  }

  // Decades on a log axis; 1-2-5 steps on a linear one.
  std::vector<double> ticks() const {
    std::vector<double> out;
    if (log) {
      const double step = std::max(1.0, std::ceil((hi - lo) / 8.0));
      for (double e = lo; e <= hi + 1e-9; e += step) out.push_back(std::pow(10.0, e));
      return out;
    }
    const double raw = (hi - lo) / 6.0;
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    const double step = raw / mag < 1.5   ? mag
                        : raw / mag < 3.5 ? 2 * mag
                        : raw / mag < 7.5 ? 5 * mag
                                          : 10 * mag;
    for (double v = std::ceil(lo / step) * step; v <= hi + step * 1e-9; v += step)
      out.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
    return out;
  }
};

}  // namespace

std::string series_colour(size_t i) {
  static const char* kPalette[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                   "#E69F00", "#56B4E9", "#F0E442", "#000000"};
  return kPalette[i % 8];
}

std::string svg_plot(const std::vector<PlotSeries>& series, const PlotOptions& o) {
  double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin, ymin = xmin, ymax = -xmin;
  size_t hidden = 0;
  for (const auto& s : series)
    for (const auto& p : s.points) {
      if (!usable(p.x, o.log_x) || !usable(p.y, o.log_y)) {
        ++hidden;
        continue;
      }
      xmin = std::min(xmin, p.x), xmax = std::max(xmax, p.x), ymin = std::min(ymin, p.y),
      ymax = std::max(ymax, p.y);
    }
  if (!std::isfinite(xmin))
    xmin = o.log_x ? 1.0 : 0.0, xmax = o.log_x ? 10.0 : 1.0, ymin = xmin, ymax = xmax;
  if (o.log_y && !std::isfinite(ymin)) ymin = 1.0, ymax = 10.0;

  const double left = 78, right = 190, top = 40, bottom = 62;
  Axis ax, ay;
  ax.log = o.log_x, ay.log = o.log_y;
  ax.fit(xmin, xmax), ay.fit(ymin, ymax);
  ax.p0 = left, ax.p1 = o.width - right;
  ay.p0 = o.height - bottom, ay.p1 = top;

  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << o.width << "\" height=\"" << o.height
    << "\" viewBox=\"0 0 " << o.width << ' ' << o.height
    << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  s << "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
  s << "<text x=\"" << px(left) << "\" y=\"24\" font-size=\"15\" font-weight=\"bold\">"
    << xml_escape(o.title) << "</text>\n";
  // Grid and ticks.
  for (double v : ax.ticks()) {
    const double x = ax.map(v);
    s << "<line x1=\"" << px(x) << "\" y1=\"" << px(ay.p1) << "\" x2=\"" << px(x) << "\" y2=\""
      << px(ay.p0) << "\" stroke=\"#e0e0e0\"/><text x=\"" << px(x) << "\" y=\"" << px(ay.p0 + 16)
      << "\" text-anchor=\"middle\">" << fmt(v) << "</text>\n";
  }
  for (double v : ay.ticks()) {
    const double y = ay.map(v);
    s << "<line x1=\"" << px(ax.p0) << "\" y1=\"" << px(y) << "\" x2=\"" << px(ax.p1) << "\" y2=\""
      << px(y) << "\" stroke=\"#e0e0e0\"/><text x=\"" << px(ax.p0 - 6) << "\" y=\"" << px(y + 4)
      << "\" text-anchor=\"end\">" << fmt(v) << "</text>\n";
  }
  s << "<rect x=\"" << px(ax.p0) << "\" y=\"" << px(ay.p1) << "\" width=\"" << px(ax.p1 - ax.p0)
    << "\" height=\"" << px(ay.p0 - ay.p1) << "\" fill=\"none\" stroke=\"#333333\"/>\n";
  s << "<text x=\"" << px((ax.p0 + ax.p1) / 2) << "\" y=\"" << px(o.height - 22.0)
    << "\" text-anchor=\"middle\">" << xml_escape(o.x_label) << (o.log_x ? " (log)" : "")
    << "</text>\n";
  s << "<text transform=\"translate(18," << px((ay.p0 + ay.p1) / 2)
    << ") rotate(-90)\" text-anchor=\"middle\">" << xml_escape(o.y_label)
    << (o.log_y ? " (log)" : "") << "</text>\n";

  // Pareto front: a staircase through the front points in cost order (each setting on the
  // front is the best accuracy available up to its cost).
  std::vector<std::pair<double, double>> front;
  for (const auto& p : o.front)
    if (usable(p.first, o.log_x) && usable(p.second, o.log_y)) front.push_back(p);
  std::sort(front.begin(), front.end());
  if (!front.empty()) {
    s << "<polyline class=\"front\" fill=\"none\" stroke=\"#444444\" stroke-width=\"1.5\" "
         "stroke-dasharray=\"5,3\" points=\"";
    for (size_t i = 0; i < front.size(); ++i) {
      if (i > 0) s << px(ax.map(front[i].first)) << ',' << px(ay.map(front[i - 1].second)) << ' ';
      s << px(ax.map(front[i].first)) << ',' << px(ay.map(front[i].second)) << ' ';
    }
    s << "\"/>\n";
  }
  if (o.fit) {
    const double x0 = std::pow(10.0, ax.lo), x1 = std::pow(10.0, ax.hi);
    auto y_of = [&](double x) {
      return std::pow(10.0, o.fit->intercept) * std::pow(x, o.fit->slope);
    };
    s << "<line class=\"fit\" x1=\"" << px(ax.map(x0)) << "\" y1=\"" << px(ay.map(y_of(x0)))
      << "\" x2=\"" << px(ax.map(x1)) << "\" y2=\"" << px(ay.map(y_of(x1)))
      << "\" stroke=\"#888888\" stroke-width=\"1.5\"/>\n";
  }
  // Clip everything data-driven to the plot area so a fit line cannot run over the labels.
  s << "<clipPath id=\"area\"><rect x=\"" << px(ax.p0) << "\" y=\"" << px(ay.p1) << "\" width=\""
    << px(ax.p1 - ax.p0) << "\" height=\"" << px(ay.p0 - ay.p1)
    << "\"/></clipPath>\n<g clip-path=\"url(#area)\">\n";
  for (size_t si = 0; si < series.size(); ++si) {
    const std::string colour = series_colour(si);
    std::vector<PlotPoint> pts;
    for (const auto& p : series[si].points)
      if (usable(p.x, o.log_x) && usable(p.y, o.log_y)) pts.push_back(p);
    if (series[si].connect && pts.size() > 1) {
      auto sorted = pts;
      std::sort(sorted.begin(), sorted.end(),
                [](const PlotPoint& a, const PlotPoint& b) { return a.x < b.x; });
      s << "<polyline fill=\"none\" stroke=\"" << colour << "\" points=\"";
      for (const auto& p : sorted) s << px(ax.map(p.x)) << ',' << px(ay.map(p.y)) << ' ';
      s << "\"/>\n";
    }
    for (const auto& p : pts) {
      const double x = ax.map(p.x), y = ay.map(p.y);
      s << "<circle class=\"" << (p.highlight ? "default" : "point") << "\" cx=\"" << px(x)
        << "\" cy=\"" << px(y) << "\" r=\"" << (p.highlight ? 6.5 : 4) << "\" fill=\"" << colour
        << "\""
        << (p.highlight ? " stroke=\"#000000\" stroke-width=\"2.5\"" : " fill-opacity=\"0.85\"")
        << "><title>" << xml_escape(series[si].name + (p.label.empty() ? "" : " " + p.label))
        << ": " << fmt(p.x) << ", " << fmt(p.y) << "</title></circle>\n";
    }
  }
  s << "</g>\n";
  // Legend.
  double ly = top + 8;
  const double lx = ax.p1 + 16;
  for (size_t si = 0; si < series.size(); ++si, ly += 20)
    s << "<circle cx=\"" << px(lx) << "\" cy=\"" << px(ly) << "\" r=\"5\" fill=\""
      << series_colour(si) << "\"/><text x=\"" << px(lx + 12) << "\" y=\"" << px(ly + 4) << "\">"
      << xml_escape(series[si].name) << "</text>\n";
  bool any_highlight = false;
  for (const auto& se : series)
    for (const auto& p : se.points) any_highlight |= p.highlight;
  if (any_highlight) {
    s << "<circle cx=\"" << px(lx) << "\" cy=\"" << px(ly)
      << "\" r=\"6\" fill=\"#ffffff\" stroke=\"#000000\" stroke-width=\"2.5\"/>"
      << "<text x=\"" << px(lx + 12) << "\" y=\"" << px(ly + 4) << "\">default setting</text>\n";
    ly += 20;
  }
  if (!front.empty()) {
    s << "<line x1=\"" << px(lx - 6) << "\" y1=\"" << px(ly) << "\" x2=\"" << px(lx + 6)
      << "\" y2=\"" << px(ly)
      << "\" stroke=\"#444444\" stroke-dasharray=\"5,3\" stroke-width=\"1.5\"/><text x=\""
      << px(lx + 12) << "\" y=\"" << px(ly + 4) << "\">Pareto front</text>\n";
    ly += 20;
  }
  if (o.fit) {
    s << "<line x1=\"" << px(lx - 6) << "\" y1=\"" << px(ly) << "\" x2=\"" << px(lx + 6)
      << "\" y2=\"" << px(ly) << "\" stroke=\"#888888\" stroke-width=\"1.5\"/><text x=\""
      << px(lx + 12) << "\" y=\"" << px(ly + 4) << "\">fit: slope " << fmt(o.fit->slope) << " (R² "
      << fmt(o.fit->r2) << ")</text>\n";
  }
  if (hidden > 0)
    s << "<text x=\"" << px(ax.p0) << "\" y=\"" << px(o.height - 6.0) << "\" fill=\"#a00000\">"
      << hidden << " point(s) not shown: not positive and finite on a log axis</text>\n";
  s << "</svg>\n";
  return s.str();
}

}  // namespace giq::gate
