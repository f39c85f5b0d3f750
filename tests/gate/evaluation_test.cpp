// Bound evaluation: PASS, WARN, FAIL, UNRESOLVED both ways, SKIP on another device, missing
// and undefined metrics, metric names resolved in single-image and sequence metrics.json.

#include "giq/gate/evaluation.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "giq/gate/config.h"
#include "giq/gate/metric_lookup.h"

namespace {

using giq::gate::Status;
using nlohmann::json;

giq::gate::Case make_case(const std::string& bounds) {
  const std::string text =
      R"({"version": 1, "cases": [{"name": "c1", "scene": "s.gltf", "technique": "t", "bounds": )" +
      bounds + "}]}";
  return giq::gate::parse_config(text, "g.json").cases[0];
}

// A metrics.json as giq score writes it for one image (docs/metrics.md).
json image_metrics() {
  return json::parse(R"({"metrics": {
    "relmse": {"value": 0.04, "definition": "relmse", "noise_floor": 0.001, "unresolved": false},
    "mse": {"value": 0.002, "noise_floor": 0.001, "unresolved": true, "note": "unresolved: reference too noisy"},
    "psnr": {"value": 31.5, "unresolved": true},
    "ssim": {"value": 0.93},
    "flip": {"mean": {"value": 0.07}, "weighted_median": {"value": 0.05}},
    "leak": {"automatic": {"leak": {"value": 0.003}}, "declared": {"leak": {"value": 0.0005}}}}})");
}

json timings(const std::string& device, double ms) {
  return {{"device", {{"name", device}}}, {"frame_gpu_ms", {{"median", ms}}}};
}

giq::gate::Evidence evidence(json m, std::optional<json> t = std::nullopt) {
  giq::gate::Evidence e;
  e.metrics = std::move(m);
  e.timings = std::move(t);
  return e;
}

TEST(GateEvaluation, PassWarnFail) {
  const auto c = make_case(R"({"relmse": {"fail": 0.05, "warn": 0.03}, "flip_mean": {"fail": 0.06},
                               "ssim": {"fail": 0.9, "warn": 0.95}, "leak": 0.001})");
  const auto o = giq::gate::evaluate(c, evidence(image_metrics()));
  ASSERT_EQ(o.size(), 4u);
  EXPECT_EQ(o[0].status, Status::Warn);  // 0.03 < 0.04 <= 0.05
  EXPECT_FALSE(o[0].fails_gate);
  EXPECT_DOUBLE_EQ(*o[0].value, 0.04);
  EXPECT_EQ(o[1].status, Status::Fail);  // flip mean 0.07 > 0.06
  EXPECT_TRUE(o[1].fails_gate);
  EXPECT_EQ(o[1].case_name, "c1");
  EXPECT_EQ(o[1].metric, "flip_mean");
  EXPECT_NE(o[1].message.find("0.07"), std::string::npos);
  EXPECT_EQ(o[2].status, Status::Warn);  // higher is better: 0.9 <= 0.93 < 0.95
  EXPECT_EQ(o[3].status, Status::Pass);  // the declared region's leak (0.0005) is the one used
  EXPECT_DOUBLE_EQ(*o[3].value, 0.0005);
  EXPECT_EQ(giq::gate::exit_code(o), 1);
  EXPECT_EQ(giq::gate::exit_code({o[0], o[2], o[3]}), 0);
}

TEST(GateEvaluation, UnresolvedIsNeverPass) {
  // mse = 0.002 is flagged unresolved. Within the bound it holds (noise only inflates the
  // measured error) but is not a PASS; beyond it the gate cannot decide and fails.
  const auto within = giq::gate::evaluate(make_case(R"({"mse": 0.01})"), evidence(image_metrics()));
  EXPECT_EQ(within[0].status, Status::Unresolved);
  EXPECT_FALSE(within[0].fails_gate);
  const auto beyond =
      giq::gate::evaluate(make_case(R"({"mse": 0.001})"), evidence(image_metrics()));
  EXPECT_EQ(beyond[0].status, Status::Unresolved);
  EXPECT_TRUE(beyond[0].fails_gate);
  EXPECT_NE(beyond[0].message.find("more samples"), std::string::npos);
  // psnr is higher-is-better: 31.5 >= 30 holds, 31.5 < 35 cannot be decided.
  EXPECT_FALSE(
      giq::gate::evaluate(make_case(R"({"psnr": 30})"), evidence(image_metrics()))[0].fails_gate);
  EXPECT_TRUE(
      giq::gate::evaluate(make_case(R"({"psnr": 35})"), evidence(image_metrics()))[0].fails_gate);
}

TEST(GateEvaluation, GpuMsOnlyOnItsDevice) {
  const auto c =
      make_case(R"({"gpu_ms": {"fail": 3, "warn": 2, "device": "h100"}, "relmse": 0.05})");
  const auto other =
      giq::gate::evaluate(c, evidence(image_metrics(), timings("llvmpipe (LLVM 15.0.6)", 40.0)));
  EXPECT_EQ(other[0].status, Status::Skip);
  EXPECT_FALSE(other[0].fails_gate);
  EXPECT_NE(other[0].message.find("llvmpipe"), std::string::npos);
  EXPECT_EQ(other[1].status, Status::Pass);
  const auto same =
      giq::gate::evaluate(c, evidence(image_metrics(), timings("NVIDIA H100 80GB HBM3", 2.5)));
  EXPECT_EQ(same[0].status, Status::Warn);  // case-insensitive device match
  const auto slow =
      giq::gate::evaluate(c, evidence(image_metrics(), timings("NVIDIA H100 80GB HBM3", 3.5)));
  EXPECT_EQ(slow[0].status, Status::Fail);
  const auto none = giq::gate::evaluate(c, evidence(image_metrics()));
  EXPECT_EQ(none[0].status, Status::Fail);  // a device bound without timings cannot be checked
}

TEST(GateEvaluation, MissingUndefinedAndProblems) {
  const auto c = make_case(R"({"flicker": 0.01, "lag90_frames": 3})");
  json seq = json::parse(R"({"sequence": {"flicker": {"value": 0.02},
      "lag90_frames": {"value": null, "definition": "lag90"},
      "lag": {"reason": "the reference has no step change"}},
      "last_frame": {"metrics": {"relmse": {"value": 0.5}}}})");
  auto o = giq::gate::evaluate(c, evidence(seq));
  EXPECT_EQ(o[0].status, Status::Fail);  // flicker 0.02 > 0.01
  EXPECT_EQ(o[1].status, Status::Fail);  // undefined is not a pass
  EXPECT_NE(o[1].message.find("undefined"), std::string::npos);

  // (A short name the catalogue lacks is a config error; a dotted path is looked up as given.)
  o = giq::gate::evaluate(make_case(R"({"relmse": 1, "metrics.no_such_metric": 1})"), evidence(seq));
  EXPECT_EQ(o[0].status, Status::Pass);  // found under last_frame.metrics
  EXPECT_EQ(o[1].status, Status::Fail);
  EXPECT_NE(o[1].message.find("no metric 'metrics.no_such_metric'"), std::string::npos);
  EXPECT_FALSE(o[1].error);  // a missing metric is the technique's failure, not infrastructure

  giq::gate::Evidence broken;
  broken.problem = "giq realtime failed (exit 134)";
  o = giq::gate::evaluate(c, broken);
  ASSERT_EQ(o.size(), 2u);
  for (const auto& x : o) {
    EXPECT_EQ(x.status, Status::Fail);
    EXPECT_EQ(x.message, broken.problem);
    EXPECT_TRUE(x.error);  // JUnit <error>: no verdict on the technique
  }
}

TEST(GateMetricLookup, PathsAndInfinities) {
  const json m =
      json::parse(R"({"metrics": {"psnr": {"value": "inf"}, "flip": {"max": {"value": 0.9}}}})");
  EXPECT_TRUE(std::isinf(*giq::gate::find_metric(m, "psnr")->value));
  EXPECT_DOUBLE_EQ(*giq::gate::find_metric(m, "flip.max")->value, 0.9);
  EXPECT_DOUBLE_EQ(*giq::gate::find_metric(m, "metrics.flip.max")->value, 0.9);
  EXPECT_EQ(giq::gate::find_metric(m, "flip_max")->path, "metrics.flip.max");
  EXPECT_FALSE(giq::gate::find_metric(m, "flip"));  // an object without a value is not a metric
  const auto t = giq::gate::frame_time(timings("X", 1.25));
  EXPECT_DOUBLE_EQ(*t.gpu_ms, 1.25);
  EXPECT_EQ(t.device, "X");
}

}  // namespace
