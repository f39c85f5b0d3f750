// Pareto front on hand-made points, the log-log slope fit on synthetic power laws, the SVG
// plot and the sweep table.

#include "giq/gate/pareto.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "giq/gate/fit.h"
#include "giq/gate/plot.h"
#include "giq/gate/sweep_table.h"

namespace {

TEST(GatePareto, HandMadePoints) {
  // (ms, error). B is dominated by A (slower and worse); D by C; E ties C exactly, so neither
  // is strictly better and both stay; F has no error (NaN) and is never on the front.
  const std::vector<giq::gate::CostError> p = {
      {1.0, 0.5},                         // A: cheapest
      {2.0, 0.6},                         // B: dominated by A
      {3.0, 0.2},                         // C
      {3.5, 0.2},                         // D: same error as C, slower -> dominated
      {3.0, 0.2},                         // E: equal to C
      {4.0, std::nan("")}, {10.0, 0.05},  // G: most accurate
      {10.0, 0.07},                       // H: same cost as G, worse -> dominated
  };
  const std::vector<bool> want = {true, false, true, false, true, false, true, false};
  EXPECT_EQ(giq::gate::pareto_front(p), want);
  EXPECT_TRUE(giq::gate::pareto_front({}).empty());
}

TEST(GateFit, RecoversKnownSlope) {
  // RMSE of a Monte Carlo estimate ~ c * spp^-1/2: exact data gives the slope to rounding.
  std::vector<double> x, y;
  for (int k = 0; k <= 10; ++k)
    x.push_back(std::pow(2.0, k)), y.push_back(0.3 * std::pow(x.back(), -0.5));
  auto f = giq::gate::fit_log_log(x, y);
  EXPECT_NEAR(f.slope, -0.5, 1e-12);
  EXPECT_NEAR(f.intercept, std::log10(0.3), 1e-12);
  EXPECT_NEAR(f.r2, 1.0, 1e-12);
  EXPECT_EQ(f.points, 11u);

  // Multiplicative noise exp(N(0, s^2)) adds N(0, (s/ln10)^2) to log10 y. The slope's
  // standard error is sigma / sqrt(sum (lx - mean)^2); 5 of them bound the estimate.
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 0.1);
  double sxx = 0.0, mean = 0.0;
  for (double v : x) mean += std::log10(v) / double(x.size());
  for (double v : x) sxx += (std::log10(v) - mean) * (std::log10(v) - mean);
  for (double& v : y) v *= std::exp(n(rng));
  f = giq::gate::fit_log_log(x, y);
  EXPECT_NEAR(f.slope, -0.5, 5.0 * (0.1 / std::log(10.0)) / std::sqrt(sxx));

  // Non-positive points are left out, not fitted as -inf.
  f = giq::gate::fit_log_log({0.0, 1.0, 10.0, -3.0}, {1.0, 1.0, 100.0, 1.0});
  EXPECT_EQ(f.points, 2u);
  EXPECT_NEAR(f.slope, 2.0, 1e-12);
  EXPECT_THROW(giq::gate::fit_log_log({1.0, 1.0}, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(giq::gate::fit_log_log({1.0}, {1.0}), std::invalid_argument);
}

TEST(GatePlot, SweepSvgHasFrontDefaultsAndEscapedNames) {
  std::vector<giq::gate::SweepRow> rows(4);
  rows[0].technique = "direct", rows[0].gpu_ms = 1.0, rows[0].metrics["flip_mean"] = 0.3,
  rows[0].is_default = true;
  rows[1].technique = "direct", rows[1].gpu_ms = 2.0, rows[1].metrics["flip_mean"] = 0.35;
  rows[2].technique = "<b>pt</b>", rows[2].gpu_ms = 8.0, rows[2].metrics["flip_mean"] = 0.05;
  rows[2].parameters = {{"samples_per_frame", 4}};
  rows[3].technique = "broken", rows[3].error = "giq realtime failed, \"exit 3\"";
  giq::gate::mark_front(rows, "flip_mean");
  EXPECT_TRUE(rows[0].on_front);
  EXPECT_FALSE(rows[1].on_front);
  EXPECT_TRUE(rows[2].on_front);
  EXPECT_FALSE(rows[3].on_front);
  const std::string svg = giq::gate::sweep_svg(rows, "flip_mean", true, "cornell / front");
  EXPECT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u);
  EXPECT_EQ(svg.find("<b>"), std::string::npos);
  EXPECT_NE(svg.find("&lt;b&gt;pt&lt;/b&gt;"), std::string::npos);
  EXPECT_NE(svg.find("class=\"front\""), std::string::npos);
  EXPECT_NE(svg.find("class=\"default\""), std::string::npos);
  EXPECT_EQ(std::count(svg.begin(), svg.end(), '\n') > 10, true);

  const std::string csv = giq::gate::sweep_csv(rows, {"flip_mean"});
  EXPECT_NE(csv.find("technique,parameters,default,gpu_ms,flip_mean,pareto_front,error\n"),
            std::string::npos);
  EXPECT_NE(csv.find("<b>pt</b>,samples_per_frame=4,0,8,0.05,1,\n"), std::string::npos);
  EXPECT_NE(csv.find("\"giq realtime failed, \"\"exit 3\"\"\""),
            std::string::npos);  // RFC 4180 quoting
  const auto back =
      giq::gate::sweep_rows(giq::gate::sweep_json(rows, "flip_mean", {}), "sweep.json");
  ASSERT_EQ(back.size(), 4u);
  EXPECT_EQ(back[2].parameters, rows[2].parameters);
  EXPECT_DOUBLE_EQ(*back[2].metrics.at("flip_mean"), 0.05);
  EXPECT_TRUE(back[2].on_front);
  EXPECT_FALSE(back[3].gpu_ms);
}

TEST(GatePlot, ConvergencePlotDrawsFit) {
  giq::gate::PlotOptions o;
  o.log_x = o.log_y = true;
  o.fit = giq::gate::LineFit{-0.5, -1.0, 1.0, 5};
  giq::gate::PlotSeries s{"rmse", {{1, 0.1}, {4, 0.05}, {16, 0.025}, {0, 1}}, true};
  const std::string svg = giq::gate::svg_plot({s}, o);
  EXPECT_NE(svg.find("class=\"fit\""), std::string::npos);
  EXPECT_NE(svg.find("slope -0.5"), std::string::npos);
  EXPECT_NE(svg.find("1 point(s) not shown"), std::string::npos);  // x = 0 on a log axis
}

}  // namespace
