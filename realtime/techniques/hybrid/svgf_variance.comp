#version 460
// SVGF, step 2 (Schied et al. 2017, section 4.2): where a pixel's history is shorter than 4
// frames its temporal moments say little, so its colour and variance come from a 7x7
// neighbourhood weighted by the edge-stopping function (the colour term at phi_colour
// luminance units, the depth term at phi_z = 3 pixel-to-pixel depth changes, as Falcor's
// SVGFPass), the variance scaled up by 4 / frames for the short history; elsewhere the
// temporal estimate passes through. With no a-trous iteration to take it from, this pass
// also writes the history (the temporal mean before any spatial filter).
#extension GL_GOOGLE_include_directive : require

#include "techniques/hybrid/svgf.glsl"
#include "techniques/hybrid/svgf_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0, rgba32f) uniform readonly image2D surface;
layout(binding = 1, rgba32f) uniform readonly image2D integrated_direct;
layout(binding = 2, rgba32f) uniform readonly image2D integrated_indirect;
layout(binding = 3, rgba32f) uniform readonly image2D moments;
layout(binding = 4, r32f) uniform readonly image2D history_length;
layout(binding = 5, rgba32f) uniform writeonly image2D out_direct;
layout(binding = 6, rgba32f) uniform writeonly image2D out_indirect;
layout(binding = 7, rgba32f) uniform writeonly image2D history_direct;
layout(binding = 8, rgba32f) uniform writeonly image2D history_indirect;

layout(push_constant) uniform Push { SvgfFilterPush pc; };

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), pc.size))) return;
  vec4 cd = imageLoad(integrated_direct, px), ci = imageLoad(integrated_indirect, px);
  float frames = imageLoad(history_length, px).x;
  if (pc.feedback != 0u) {  // the unfiltered temporal mean is next frame's history
    imageStore(history_direct, px, cd);
    imageStore(history_indirect, px, ci);
  }
  SvgfSurface p = svgf_surface(imageLoad(surface, px));
  if (p.z <= 0.0 || frames >= 4.0) {
    imageStore(out_direct, px, cd);
    imageStore(out_indirect, px, ci);
    return;
  }
  float ld = svgf_luminance(cd.rgb), li = svgf_luminance(ci.rgb);
  p.dz *= 3.0;
  vec3 sd = vec3(0.0), si = vec3(0.0);
  vec4 sm_d = vec4(0.0), sm_i = vec4(0.0);
  float wd = 0.0, wi = 0.0;
  for (int j = -3; j <= 3; ++j)
    for (int i = -3; i <= 3; ++i) {
      ivec2 q = px + ivec2(i, j);
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(uvec2(q), pc.size))) continue;
      SvgfSurface s = svgf_surface(imageLoad(surface, q));
      vec4 qd = imageLoad(integrated_direct, q), qi = imageLoad(integrated_indirect, q);
      vec4 m = imageLoad(moments, q);
      float dist = max(length(vec2(i, j)), 1.0);  // the centre pixel: weight 1 whatever dist
      float w1 = svgf_weight(p, s, dist, ld, svgf_luminance(qd.rgb), pc.phi_colour, pc.phi_normal);
      float w2 = svgf_weight(p, s, dist, li, svgf_luminance(qi.rgb), pc.phi_colour, pc.phi_normal);
      sd += w1 * qd.rgb, sm_d.xy += w1 * m.xy, wd += w1;
      si += w2 * qi.rgb, sm_i.xy += w2 * m.zw, wi += w2;
    }
  wd = max(wd, 1e-6);
  wi = max(wi, 1e-6);
  sm_d /= wd;
  sm_i /= wi;
  float boost = 4.0 / max(frames, 1.0);
  imageStore(out_direct, px, vec4(sd / wd, max(0.0, sm_d.y - sm_d.x * sm_d.x) * boost));
  imageStore(out_indirect, px, vec4(si / wi, max(0.0, sm_i.y - sm_i.x * sm_i.x) * boost));
}
