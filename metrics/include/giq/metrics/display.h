#pragma once
// The display transform `giq score` applies to the reference before comparing it with an
// image an engine wrote after its own exposure and tone mapping (docs/own-engine.md): an
// exposure in stops, then a tone curve, per channel, on scene-linear radiance. The exposure
// goes on the reference only (the test carries its own); the tone curve goes on an HDR test
// too, so that both are display-referred (an 8-bit test already is).
//
// The curves, each mapping scene-linear x >= 0 to display-linear [0, 1]:
//   clamp     min(x, 1)
//   reinhard  x / (1 + x)                                    (Reinhard et al. 2002, eq. 3)
//   aces      x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), clamped to [0, 1]
//             (Narkowicz 2016, "ACES Filmic Tone Mapping Curve": the fit of the ACES RRT+ODT
//             that Unreal Engine 4 and many engines ship)
//   hable     h(x) / h(11.2), h(x) = (x (A x + C B) + D E) / (x (A x + B) + D F) - E / F with
//             A 0.15, B 0.50, C 0.10, D 0.20, E 0.02, F 0.30 (Hable 2010, "Uncharted 2:
//             HDR Lighting", the filmic curve with white point W = 11.2; no exposure bias)
// The reference's variance goes through the same map to first order (the delta method:
// Var f(s x) = (s f'(s x))^2 Var x), so the noise floors stay the golden's own.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

namespace giq::metrics {

enum class ToneCurve { None, Clamp, Reinhard, Aces, Hable };

// "none", "clamp", "reinhard", "aces", "hable"; empty for any other name.
std::optional<ToneCurve> tone_curve_from_name(std::string_view name);
std::string_view tone_curve_name(ToneCurve c);
inline constexpr std::string_view kToneCurveNames = "none, clamp, reinhard, aces, hable";

// none: x as is; the others: x < 0 as 0, +inf as the curve's limit; NaN stays NaN.
float tone_curve(ToneCurve c, float x);
float tone_curve_slope(ToneCurve c, float x);  // d tone_curve / dx; 0 where the curve is flat (clamped)

struct DisplayTransform {
  double exposure_ev = 0.0;  // radiance x 2^exposure_ev before the curve
  ToneCurve curve = ToneCurve::None;
  bool active() const { return exposure_ev != 0.0 || curve != ToneCurve::None; }
  float apply(float x) const;
  float slope(float x) const;  // d apply / dx
  nlohmann::json to_json() const;
};

}  // namespace giq::metrics
