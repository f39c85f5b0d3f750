#pragma once
// FLIP's convolution kernels, all separable: the contrast sensitivity (CSF) filters of the colour
// pipeline and the edge/point detectors of the feature pipeline, sized from pixels per degree.

#include <vector>

namespace giq::metrics::flip {

// [FLIP] colour pipeline, spatial filtering. Each 2D kernel is a sum of separable terms
// w(x) w(y): Y and Cx have one term, Cz two (its CSF is a sum of two Gaussians, so the 2D
// kernel is c1 g1(x)g1(y) + c2 g2(x)g2(y), split into one separable term per Gaussian).
// Every 2D kernel sums to 1, so a constant colour passes unchanged.
struct CsfFilters {
  int radius = 0;
  std::vector<float> y, cx, cz1, cz2;  // 2 radius + 1 taps each
};
CsfFilters make_csf_filters(float pixels_per_degree);

// [FLIP] feature pipeline: a Gaussian, its first derivative (edges) and its second derivative
// (points), standard deviation 0.5 w pixels_per_degree. The Gaussian sums to 1; each derivative
// has its positive weights scaled to sum to 1 and its negative weights to -1, which bounds the
// response to [0,1] input by 1 and makes a derivative of a constant exactly 0.
struct FeatureFilters {
  int radius = 0;
  std::vector<float> gaussian, first, second;
};
FeatureFilters make_feature_filters(float pixels_per_degree);

}  // namespace giq::metrics::flip
