#pragma once
// The constants of FLIP and HDR-FLIP, named as in the papers:
//   [FLIP]    Andersson, Nilsson, Akenine-Moeller, Oskarsson, Astroem, Fairchild, "FLIP: A
//             Difference Evaluator for Alternating Images", Proc. ACM CGIT 3(2), HPG 2020.
//   [HDRFLIP] Andersson, Nilsson, Shirley, Akenine-Moeller, "Visualizing Errors in Rendered High
//             Dynamic Range Images", Eurographics 2021 short papers; also Ray Tracing Gems II,
//             ch. 19, "Visualizing and Communicating Errors in Rendered Images", 2021.
// Every value below is the one the papers give and NVIDIA's reference implementation uses; the
// agreement tests (tests/metrics/flip_test.cpp) would fail if one drifted.

namespace giq::metrics::flip {

// [FLIP] colour pipeline, spatial filtering: each opponent channel's contrast sensitivity
// function is a sum of Gaussians in the frequency domain, CSF(f) = a1 exp(-b1 f^2) + a2 exp(-b2 f^2),
// whose spatial-domain filter is sum_i a_i sqrt(pi / b_i) exp(-pi^2 x^2 / b_i) (x in degrees).
struct CsfGaussians {
  float a1, b1, a2, b2;
};
inline constexpr CsfGaussians kCsfAchromatic{1.0f, 0.0047f, 0.0f, 1.0e-5f};  // Y
inline constexpr CsfGaussians kCsfRedGreen{1.0f, 0.0053f, 0.0f, 1.0e-5f};    // Cx
inline constexpr CsfGaussians kCsfBlueYellow{34.1f, 0.04f, 13.5f, 0.025f};   // Cz
// The widest of the b parameters sets the filter radius: 3 standard deviations of the widest
// spatial Gaussian, whose standard deviation is sqrt(b / (2 pi^2)) degrees.
inline constexpr float kCsfWidestB = 0.04f;
inline constexpr float kCsfRadiusInStdDevs = 3.0f;

// [FLIP] colour pipeline, colour metric: the HyAB distance of Hunt-adjusted L*a*b* colours is
// raised to qc, then redistributed so that the fraction pc of the largest possible difference
// cmax (green against blue) maps to pt, compressing the large differences into (pt, 1].
inline constexpr float kColourExponentQc = 0.7f;
inline constexpr float kColourCutoffPc = 0.4f;
inline constexpr float kColourCutoffPt = 0.95f;
// [FLIP] Hunt effect: chroma scaled by 0.01 L* (colourfulness grows with luminance).
inline constexpr float kHuntFactor = 0.01f;

// [FLIP] feature pipeline: edges and points are detected on achromatic values normalised to
// [0, 1], with the first and second derivatives of a Gaussian whose standard deviation is
// 0.5 w degrees, w = 0.082 degrees; the filter is 3 standard deviations wide on each side.
inline constexpr float kFeatureWidthDegrees = 0.082f;
inline constexpr float kFeatureRadiusInStdDevs = 3.0f;
// [FLIP] feature difference: max(|edge_R - edge_T|, |point_R - point_T|) / sqrt(2), raised to qf.
inline constexpr float kFeatureExponentQf = 0.5f;

// [HDRFLIP] exposure range: the tone mapper maps the exposure-scaled luminance x_max to 0.85,
// the largest display value that is still clearly distinguishable from white.
inline constexpr float kToneMappedTarget = 0.85f;

// CIE 1976 L*a*b*: the threshold of the cube-root branch is (6/29)^3.
inline constexpr float kLabDelta = 6.0f / 29.0f;

}  // namespace giq::metrics::flip
