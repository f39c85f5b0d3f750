// Shadow-map lookups for the layers written by passes/shadow_maps.cpp: PCF over a
// (2r+1)^2 grid of texels with hardware depth comparison, after offsetting the receiver
// along its normal by `normal_offset` texels (the texel's world size at that distance).
// The includer declares `shadow_map` (sampler2DArrayShadow) and `shadow_layers`.
#ifndef GIQ_SHADOW_GLSL
#define GIQ_SHADOW_GLSL

#include "passes/shadow_maps_shared.h"

float shadow_pcf(uint layer, vec3 p, int radius) {
  vec4 c = shadow_layers[layer].view_proj * vec4(p, 1.0);
  if (c.w <= 0.0) return 1.0;
  vec3 ndc = c.xyz / c.w;
  // A layer may use only its corner (ShadowMaps::add_cube's size): taps stay inside it, as
  // clamping to the edge keeps them inside a whole layer.
  float used = shadow_layers[layer].params.w;
  vec2 uv = (ndc.xy * 0.5 + 0.5) * used;
  if (ndc.z >= 1.0) return 1.0;  // beyond the far plane: nothing there casts
  float texel = 1.0 / float(textureSize(shadow_map, 0).x);
  float lit = 0.0;
  for (int j = -radius; j <= radius; ++j)
    for (int i = -radius; i <= radius; ++i)
      lit += texture(shadow_map, vec4(clamp(uv + vec2(i, j) * texel, vec2(0.5 * texel), vec2(used - 0.5 * texel)), float(layer), ndc.z));
  float n = float(2 * radius + 1);
  return lit / (n * n);
}

// Cube layers first_layer .. first_layer + 5 around `center`.
float shadow_cube(uint first_layer, vec3 center, vec3 p, vec3 n, float normal_offset, int radius) {
  float dist = length(p - center);
  vec3 q = p + n * (normal_offset * shadow_layers[first_layer].params.y * dist);
  vec3 d = q - center;
  vec3 ad = abs(d);
  uint face = ad.x >= ad.y && ad.x >= ad.z ? (d.x >= 0.0 ? 0u : 1u)
            : ad.y >= ad.z                 ? (d.y >= 0.0 ? 2u : 3u)
                                           : (d.z >= 0.0 ? 4u : 5u);
  return shadow_pcf(first_layer + face, q, radius);
}

// Cascades first_layer .. first_layer + 2, chosen by the distance along the view.
float shadow_cascades(uint first_layer, float view_depth, vec3 p, vec3 n, float normal_offset, int radius) {
  uint c = 0u;
  while (c < 2u && view_depth > shadow_layers[first_layer + c].params.z) ++c;
  vec3 q = p + n * (normal_offset * shadow_layers[first_layer + c].params.y);
  return shadow_pcf(first_layer + c, q, radius);
}

#endif
