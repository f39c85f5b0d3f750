#pragma once
// FLIP's colour transforms, one per step of [FLIP]'s colour pipeline. Each works on one pixel
// (T = float) or four (T = Float4, fast_math.h); they are inline because the error-map passes
// call them in their innermost loops.
// Sources: IEC 61966-2-1 (sRGB primaries, D65 white), CIE 15 (L*a*b*), [FLIP] (see constants.h)
// for YCxCz, the Hunt adjustment, HyAB and the error redistribution.

#include <algorithm>
#include <cmath>

#include "constants.h"
#include "fast_math.h"

namespace giq::metrics::flip {

template <class T>
struct ColourT {
  T c0, c1, c2;  // (R,G,B), (X,Y,Z), (Y,Cx,Cz) or (L*,a*,b*) depending on the space
};
using Colour = ColourT<float>;

// Linear RGB with sRGB/BT.709 primaries -> CIE XYZ, D65 white. The exact rational form of the
// IEC 61966-2-1 matrix, so that RGB white maps to a white point with Y = 1 exactly.
inline constexpr double kRgbToXyz[3][3] = {
    {10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0},
    {2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0},
    {1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0}};

namespace detail {
struct Matrix3 {
  float m[3][3];
};
constexpr Matrix3 to_float(const double (&a)[3][3]) {
  Matrix3 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.m[i][j] = float(a[i][j]);
  return r;
}
// The inverse by cofactors, evaluated in double at compile time.
constexpr Matrix3 inverse_to_float(const double (&a)[3][3]) {
  const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                     a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                     a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  double inv[3][3] = {
      {(a[1][1] * a[2][2] - a[1][2] * a[2][1]) / det, (a[0][2] * a[2][1] - a[0][1] * a[2][2]) / det,
       (a[0][1] * a[1][2] - a[0][2] * a[1][1]) / det},
      {(a[1][2] * a[2][0] - a[1][0] * a[2][2]) / det, (a[0][0] * a[2][2] - a[0][2] * a[2][0]) / det,
       (a[0][2] * a[1][0] - a[0][0] * a[1][2]) / det},
      {(a[1][0] * a[2][1] - a[1][1] * a[2][0]) / det, (a[0][1] * a[2][0] - a[0][0] * a[2][1]) / det,
       (a[0][0] * a[1][1] - a[0][1] * a[1][0]) / det}};
  return to_float(inv);
}
}  // namespace detail

inline constexpr detail::Matrix3 kRgbToXyzF = detail::to_float(kRgbToXyz);
inline constexpr detail::Matrix3 kXyzToRgbF = detail::inverse_to_float(kRgbToXyz);
// D65 reference white = XYZ of RGB (1, 1, 1); L*a*b* and YCxCz divide by it.
inline constexpr float kWhiteX = float(kRgbToXyz[0][0] + kRgbToXyz[0][1] + kRgbToXyz[0][2]);
inline constexpr float kWhiteY = 1.0f;
inline constexpr float kWhiteZ = float(kRgbToXyz[2][0] + kRgbToXyz[2][1] + kRgbToXyz[2][2]);
inline constexpr float kInvWhiteX = float(1.0 / (kRgbToXyz[0][0] + kRgbToXyz[0][1] + kRgbToXyz[0][2]));
inline constexpr float kInvWhiteZ = float(1.0 / (kRgbToXyz[2][0] + kRgbToXyz[2][1] + kRgbToXyz[2][2]));

template <class T>
inline ColourT<T> linear_rgb_to_xyz(ColourT<T> rgb) {
  const auto& m = kRgbToXyzF.m;
  return {m[0][0] * rgb.c0 + m[0][1] * rgb.c1 + m[0][2] * rgb.c2,
          m[1][0] * rgb.c0 + m[1][1] * rgb.c1 + m[1][2] * rgb.c2,
          m[2][0] * rgb.c0 + m[2][1] * rgb.c1 + m[2][2] * rgb.c2};
}

template <class T>
inline ColourT<T> xyz_to_linear_rgb(ColourT<T> xyz) {
  const auto& m = kXyzToRgbF.m;
  return {m[0][0] * xyz.c0 + m[0][1] * xyz.c1 + m[0][2] * xyz.c2,
          m[1][0] * xyz.c0 + m[1][1] * xyz.c1 + m[1][2] * xyz.c2,
          m[2][0] * xyz.c0 + m[2][1] * xyz.c1 + m[2][2] * xyz.c2};
}

// [FLIP] colour pipeline: the opponent space YCxCz is L*a*b* without the cube root, i.e. linear
// in XYZ, so that the contrast sensitivity filters act on a linear signal:
//   Y = 116 Y/Yn - 16,  Cx = 500 (X/Xn - Y/Yn),  Cz = 200 (Y/Yn - Z/Zn).
template <class T>
inline ColourT<T> xyz_to_ycxcz(ColourT<T> xyz) {
  const T x = xyz.c0 * kInvWhiteX, y = xyz.c1, z = xyz.c2 * kInvWhiteZ;
  return {116.0f * y - 16.0f, 500.0f * (x - y), 200.0f * (y - z)};
}

template <class T>
inline ColourT<T> ycxcz_to_xyz(ColourT<T> ycxcz) {
  const T y = (ycxcz.c0 + 16.0f) / 116.0f;
  const T x = y + ycxcz.c1 / 500.0f;
  const T z = y - ycxcz.c2 / 200.0f;
  return {x * kWhiteX, y * kWhiteY, z * kWhiteZ};
}

template <class T>
inline T clamp01(T v) { return vmin(vmax(v, splat<T>(0.0f)), splat<T>(1.0f)); }
template <class T>
inline ColourT<T> clamp01(ColourT<T> c) { return {clamp01(c.c0), clamp01(c.c1), clamp01(c.c2)}; }

// CIE 1976 L*a*b* with the D65 white above: f(t) = t^(1/3) above (6/29)^3, else the linear
// segment t / (3 (6/29)^2) + 4/29.
template <class T>
inline T lab_f(T t) {
  constexpr float kDelta3 = kLabDelta * kLabDelta * kLabDelta;
  constexpr float kSlope = 1.0f / (3.0f * kLabDelta * kLabDelta);
  return t > splat<T>(kDelta3) ? fast_cbrt(vmax(t, splat<T>(kDelta3))) : kSlope * t + 4.0f / 29.0f;
}

template <class T>
inline ColourT<T> xyz_to_lab(ColourT<T> xyz) {
  const T fx = lab_f(xyz.c0 * kInvWhiteX), fy = lab_f(xyz.c1), fz = lab_f(xyz.c2 * kInvWhiteZ);
  return {116.0f * fy - 16.0f, 500.0f * (fx - fy), 200.0f * (fy - fz)};
}

// [FLIP] Hunt adjustment: a* and b* scaled by 0.01 L*, since chroma differences are perceived
// more strongly at higher luminance.
template <class T>
inline ColourT<T> hunt_adjust(ColourT<T> lab) {
  const T s = kHuntFactor * lab.c0;
  return {lab.c0, s * lab.c1, s * lab.c2};
}

// [FLIP] HyAB (Abasi et al. 2020): city-block distance in L*, Euclidean in (a*, b*); better
// than Euclidean Delta E for large colour differences.
template <class T>
inline T hyab(ColourT<T> a, ColourT<T> b) {
  const T da = a.c1 - b.c1, db = a.c2 - b.c2;
  return vabs(a.c0 - b.c0) + vsqrt(da * da + db * db);
}

// Linear RGB in [0,1] after spatial filtering -> Hunt-adjusted L*a*b*, where [FLIP] measures
// the colour difference.
template <class T>
inline ColourT<T> linear_rgb_to_hunt_lab(ColourT<T> rgb) { return hunt_adjust(xyz_to_lab(linear_rgb_to_xyz(rgb))); }

// [FLIP] cmax: the largest HyAB^qc difference between two colours of the [0,1] RGB cube, that of
// pure green and pure blue (Hunt-adjusted).
inline float max_colour_difference() {
  const float d = hyab(linear_rgb_to_hunt_lab(Colour{0.0f, 1.0f, 0.0f}), linear_rgb_to_hunt_lab(Colour{0.0f, 0.0f, 1.0f}));
  return std::pow(d, kColourExponentQc);
}

// [FLIP] error redistribution: e = HyAB^qc; e < pc cmax maps linearly onto [0, pt), the rest
// onto [pt, 1], so that small, visible differences get most of the output range.
struct ColourRedistribution {
  float cmax;
  float pc_cmax;  // pc * cmax
  float below_scale;  // pt / (pc cmax)
  float above_scale;  // (1 - pt) / (cmax - pc cmax)
};
inline ColourRedistribution make_colour_redistribution() {
  const float cmax = max_colour_difference();
  const float pc_cmax = kColourCutoffPc * cmax;
  return {cmax, pc_cmax, kColourCutoffPt / pc_cmax, (1.0f - kColourCutoffPt) / (cmax - pc_cmax)};
}
template <class T>
inline T redistribute_colour_error(T hyab_distance, const ColourRedistribution& r) {
  const T e = fast_pow(hyab_distance, splat<T>(kColourExponentQc));
  return e < splat<T>(r.pc_cmax) ? e * r.below_scale : kColourCutoffPt + (e - r.pc_cmax) * r.above_scale;
}

// [FLIP] feature difference: the larger of the edge and point differences, normalised by
// 1/sqrt(2) (the largest magnitude of a 2D gradient of [0,1] values with the normalised
// filters), raised to qf.
template <class T>
inline T feature_difference(T edge_difference, T point_difference) {
  constexpr float kInvSqrt2 = 0.70710678118654752f;
  static_assert(kFeatureExponentQf == 0.5f, "qf = 0.5 is a square root");
  return vsqrt(kInvSqrt2 * vmax(edge_difference, point_difference));
}

// [FLIP] final difference map: Delta E = Delta E_c ^ (1 - Delta E_f): features amplify colour
// differences where edges or points differ.
template <class T>
inline T combine_differences(T colour_difference, T feature_difference) {
  return fast_pow(colour_difference, 1.0f - feature_difference);
}

}  // namespace giq::metrics::flip
