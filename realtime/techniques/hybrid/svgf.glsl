// What the SVGF passes share (svgf.h): the surface at a pixel as svgf_shared.h stores it, and
// the edge-stopping weight between two pixels (Schied et al. 2017, eq. 3-5).
#ifndef GIQ_SVGF_GLSL
#define GIQ_SVGF_GLSL

#include "shaders/octahedral.glsl"

// Demodulation divides by the albedo and remodulation multiplies by the same value, floored
// here so that black surfaces stay finite (their light is 0 either way).
const float kSvgfAlbedoFloor = 1e-3;

// The luminance the moments and the colour edge-stopping function take (Rec. 709).
float svgf_luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

struct SvgfSurface {
  vec3 n;      // shading normal
  float z;     // linear depth; 0: no surface
  float dz;    // depth change per pixel on this surface (svgf_shared.h)
};

SvgfSurface svgf_surface(vec4 texel) {
  SvgfSurface s;
  s.n = oct_decode(texel.xy);
  s.z = texel.z;
  s.dz = texel.w;
  return s;
}

// w(p, q) = exp(-|z_p - z_q| / (phi_z |dz_p| |p - q|) - |l_p - l_q| / phi_l) max(0, n_p.n_q)^phi_n
// (eq. 3-5 with sigma_z = 1; `distance` is |p - q| in pixels, phi_l the colour term's scale).
float svgf_weight(SvgfSurface p, SvgfSurface q, float distance, float lp, float lq, float phi_l, float phi_normal) {
  if (q.z <= 0.0) return 0.0;
  float w_normal = pow(clamp(dot(p.n, q.n), 0.0, 1.0), phi_normal);
  float w_z = abs(p.z - q.z) / (p.dz * distance);
  float w_l = abs(lp - lq) / phi_l;
  return exp(-w_z - w_l) * w_normal;
}

#endif
