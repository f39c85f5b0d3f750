#version 460
// SVGF, step 4: the filtered light multiplied back by the albedo it was divided by
// (svgf_reproject.comp), and the light that needed no filtering (emission and background seen
// directly) added to the first signal. Also writes the history length as a layer.
#extension GL_GOOGLE_include_directive : require

#include "techniques/hybrid/svgf.glsl"
#include "techniques/hybrid/svgf_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0, rgba32f) uniform readonly image2D filtered_direct;
layout(binding = 1, rgba32f) uniform readonly image2D filtered_indirect;
layout(binding = 2, rgba32f) uniform readonly image2D albedo;
layout(binding = 3, rgba32f) uniform readonly image2D unfiltered;
layout(binding = 4, r32f) uniform readonly image2D history_length;
layout(binding = 5, rgba32f) uniform writeonly image2D out_direct;
layout(binding = 6, rgba32f) uniform writeonly image2D out_indirect;
layout(binding = 7, rgba32f) uniform writeonly image2D out_history;

layout(push_constant) uniform Push { SvgfModulatePush pc; };


void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), pc.size))) return;
  vec3 a = imageLoad(albedo, px).rgb;
  vec3 m = any(greaterThan(a, vec3(0.0))) ? max(a, vec3(kSvgfAlbedoFloor)) : vec3(0.0);
  imageStore(out_direct, px, vec4(imageLoad(filtered_direct, px).rgb * m + imageLoad(unfiltered, px).rgb, 1.0));
  imageStore(out_indirect, px, vec4(imageLoad(filtered_indirect, px).rgb * m, 1.0));
  imageStore(out_history, px, vec4(imageLoad(history_length, px).x, 0.0, 0.0, 1.0));
}
