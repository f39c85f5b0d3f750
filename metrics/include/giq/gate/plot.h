#pragma once
// Scatter plots as standalone SVG 1.1 (no plotting library; any browser shows them): error
// against GPU ms for sweeps, with several techniques in different colours, each technique's
// default setting ringed, and the Pareto front as a staircase; error against spp or seconds
// for reference convergence, with the fitted power law as a straight line on log-log axes.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "giq/gate/fit.h"

namespace giq::gate {

struct PlotPoint {
  double x = 0.0, y = 0.0;
  bool highlight = false;  // drawn larger and ringed (a technique's default setting)
  std::string label;       // tooltip (<title>)
};

struct PlotSeries {
  std::string name;
  std::vector<PlotPoint> points;
  bool connect = false;  // join the points in x order
};

struct PlotOptions {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;
  int width = 760, height = 480;
  std::vector<std::pair<double, double>> front;  // Pareto front points (any order)
  std::optional<LineFit> fit;                    // drawn as y = 10^intercept * x^slope
};

// Points that a log axis cannot show (x or y <= 0, non-finite) are left out and counted in a
// note under the plot.
std::string svg_plot(const std::vector<PlotSeries>& series, const PlotOptions& options);

// The colour of series i ("#rrggbb"), a palette distinguishable for common colour-vision
// deficiencies (Okabe and Ito 2008, "Color Universal Design").
std::string series_colour(size_t i);

}  // namespace giq::gate
