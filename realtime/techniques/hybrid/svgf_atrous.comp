#version 460
// SVGF, step 3 (Schied et al. 2017, section 4.3; Dammertz et al. 2010): one iteration of the
// edge-avoiding a-trous wavelet filter, a 5x5 B3-spline kernel (1/16, 1/4, 3/8, 1/4, 1/16 per
// axis) with holes, its taps `step` pixels apart, each weighted by the edge-stopping function
// (eq. 3-5): luminance differences in units of phi_colour standard deviations of the
// pixel's luminance (its variance prefiltered by a 3x3 Gaussian, eq. 5), normals by the power
// phi_normal of their cosine, depths in units of the depth change over the tap's distance.
// The variance is filtered with the squared weights (eq. 2), so that each iteration's
// variance is the variance of its output.
#extension GL_GOOGLE_include_directive : require

#include "techniques/hybrid/svgf.glsl"
#include "techniques/hybrid/svgf_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0, rgba32f) uniform readonly image2D surface;
layout(binding = 1, rgba32f) uniform readonly image2D in_direct;
layout(binding = 2, rgba32f) uniform readonly image2D in_indirect;
layout(binding = 3, rgba32f) uniform writeonly image2D out_direct;
layout(binding = 4, rgba32f) uniform writeonly image2D out_indirect;
layout(binding = 5, rgba32f) uniform writeonly image2D history_direct;
layout(binding = 6, rgba32f) uniform writeonly image2D history_indirect;

layout(push_constant) uniform Push { SvgfFilterPush pc; };

bool inside(ivec2 q) { return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(uvec2(q), pc.size)); }

// The variance at px through a 3x3 Gaussian (eq. 5's g_3x3), for direct (x) and indirect (y).
vec2 prefiltered_variance(ivec2 px) {
  vec2 sum = vec2(0.0);
  float wsum = 0.0;
  for (int j = -1; j <= 1; ++j)
    for (int i = -1; i <= 1; ++i) {
      ivec2 q = px + ivec2(i, j);
      if (!inside(q)) continue;
      float w = (i == 0 ? 0.5 : 0.25) * (j == 0 ? 0.5 : 0.25);  // (1, 2, 1) / 4 per axis
      sum += w * vec2(imageLoad(in_direct, q).a, imageLoad(in_indirect, q).a);
      wsum += w;
    }
  return sum / wsum;
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), pc.size))) return;
  vec4 cd = imageLoad(in_direct, px), ci = imageLoad(in_indirect, px);
  SvgfSurface p = svgf_surface(imageLoad(surface, px));
  if (p.z > 0.0) {
    vec2 var = prefiltered_variance(px);
    // phi_colour standard deviations; the 1e-10 keeps a noise-free pixel's scale positive.
    float phi_d = pc.phi_colour * sqrt(max(0.0, 1e-10 + var.x));
    float phi_i = pc.phi_colour * sqrt(max(0.0, 1e-10 + var.y));
    float ld = svgf_luminance(cd.rgb), li = svgf_luminance(ci.rgb);
    p.dz *= float(pc.step);
    // The B3 spline (1, 4, 6, 4, 1) / 16 per axis, scaled so the centre tap weighs 1.
    const float kernel[3] = float[3](1.0, 2.0 / 3.0, 1.0 / 6.0);
    vec4 sd = cd, si = ci;
    float wd = 1.0, wi = 1.0;
    for (int j = -2; j <= 2; ++j)
      for (int i = -2; i <= 2; ++i) {
        if (i == 0 && j == 0) continue;
        ivec2 q = px + pc.step * ivec2(i, j);
        if (!inside(q)) continue;
        SvgfSurface s = svgf_surface(imageLoad(surface, q));
        vec4 qd = imageLoad(in_direct, q), qi = imageLoad(in_indirect, q);
        float h = kernel[abs(i)] * kernel[abs(j)], dist = length(vec2(i, j));
        float w1 = h * svgf_weight(p, s, dist, ld, svgf_luminance(qd.rgb), phi_d, pc.phi_normal);
        float w2 = h * svgf_weight(p, s, dist, li, svgf_luminance(qi.rgb), phi_i, pc.phi_normal);
        sd += vec4(w1, w1, w1, w1 * w1) * qd, wd += w1;
        si += vec4(w2, w2, w2, w2 * w2) * qi, wi += w2;
      }
    cd = sd / vec4(wd, wd, wd, wd * wd);
    ci = si / vec4(wi, wi, wi, wi * wi);
  }
  imageStore(out_direct, px, cd);
  imageStore(out_indirect, px, ci);
  if (pc.feedback != 0u) {
    imageStore(history_direct, px, cd);
    imageStore(history_indirect, px, ci);
  }
}
