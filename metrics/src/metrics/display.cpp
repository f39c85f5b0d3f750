#include "giq/metrics/display.h"

#include <algorithm>
#include <cmath>

namespace giq::metrics {
namespace {

// Hable 2010's constants and the white point.
constexpr double kA = 0.15, kB = 0.50, kC = 0.10, kD = 0.20, kE = 0.02, kF = 0.30, kWhite = 11.2;

double hable(double x) { return (x * (kA * x + kC * kB) + kD * kE) / (x * (kA * x + kB) + kD * kF) - kE / kF; }
double hable_slope(double x) {
  const double n = x * (kA * x + kC * kB) + kD * kE, m = x * (kA * x + kB) + kD * kF;
  return ((2.0 * kA * x + kC * kB) * m - n * (2.0 * kA * x + kB)) / (m * m);
}

double aces(double x) { return x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14); }
double aces_slope(double x) {
  const double n = x * (2.51 * x + 0.03), m = x * (2.43 * x + 0.59) + 0.14;
  return ((5.02 * x + 0.03) * m - n * (4.86 * x + 0.59)) / (m * m);
}

}  // namespace

std::optional<ToneCurve> tone_curve_from_name(std::string_view name) {
  for (ToneCurve c : {ToneCurve::None, ToneCurve::Clamp, ToneCurve::Reinhard, ToneCurve::Aces, ToneCurve::Hable})
    if (tone_curve_name(c) == name) return c;
  return std::nullopt;
}

std::string_view tone_curve_name(ToneCurve c) {
  switch (c) {
    case ToneCurve::None: return "none";
    case ToneCurve::Clamp: return "clamp";
    case ToneCurve::Reinhard: return "reinhard";
    case ToneCurve::Aces: return "aces";
    case ToneCurve::Hable: return "hable";
  }
  return "none";
}

float tone_curve(ToneCurve c, float xf) {
  if (std::isnan(xf) || c == ToneCurve::None) return xf;
  const double x = std::max(double(xf), 0.0);
  switch (c) {
    case ToneCurve::None: return float(x);
    case ToneCurve::Clamp: return float(std::min(x, 1.0));
    case ToneCurve::Reinhard: return std::isinf(x) ? 1.0f : float(x / (1.0 + x));
    case ToneCurve::Aces: return std::isinf(x) ? 1.0f : float(std::clamp(aces(x), 0.0, 1.0));
    case ToneCurve::Hable: return float((std::isinf(x) ? 1.0 - kE / kF : hable(x)) / hable(kWhite));
  }
  return float(x);
}

float tone_curve_slope(ToneCurve c, float xf) {
  if (std::isnan(xf)) return xf;
  if (c == ToneCurve::None) return 1.0f;
  if (xf < 0.0f) return 0.0f;
  const double x = xf;
  if (std::isinf(x)) return c == ToneCurve::None ? 1.0f : 0.0f;
  switch (c) {
    case ToneCurve::None: return 1.0f;
    case ToneCurve::Clamp: return x < 1.0 ? 1.0f : 0.0f;
    case ToneCurve::Reinhard: return float(1.0 / ((1.0 + x) * (1.0 + x)));
    case ToneCurve::Aces: return aces(x) >= 1.0 ? 0.0f : float(aces_slope(x));
    case ToneCurve::Hable: return float(hable_slope(x) / hable(kWhite));
  }
  return 1.0f;
}

float DisplayTransform::apply(float x) const { return tone_curve(curve, float(std::exp2(exposure_ev) * double(x))); }

float DisplayTransform::slope(float x) const {
  const double s = std::exp2(exposure_ev);
  return float(s * double(tone_curve_slope(curve, float(s * double(x)))));
}

nlohmann::json DisplayTransform::to_json() const {
  return {{"exposure_ev", exposure_ev},
          {"tone_curve", std::string(tone_curve_name(curve))},
          {"applied_to", "exposure: the reference; tone curve: the reference, and the test when it is HDR"}};
}

}  // namespace giq::metrics
