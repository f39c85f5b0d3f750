// The DDGI probe volume as every DDGI shader reads it: probe positions, ray directions and the
// irradiance query (Majercik et al. 2019 and its reference GLSL code; Majercik et al. 2021 for
// the relocation offsets and probe states). The includer declares
//   ddgi          GpuDdgiVolume
//   ddgi_probes[] GpuDdgiProbe
//   ddgi_irradiance, ddgi_distance  sampler2D (bilinear, clamped) over the two atlases
// (only ddgi_irradiance_at needs the samplers). Needs sampling.glsl (PI).
#ifndef GIQ_DDGI_VOLUME_GLSL
#define GIQ_DDGI_VOLUME_GLSL

#include "techniques/ddgi/ddgi_shared.h"
#include "shaders/octahedral.glsl"

uvec3 ddgi_probe_coords(uint p) {
  uvec3 c = ddgi.counts.xyz;
  return uvec3(p % c.x, (p / c.x) % c.y, p / (c.x * c.y));
}

uint ddgi_probe_index(uvec3 g) { return g.x + ddgi.counts.x * (g.y + ddgi.counts.y * g.z); }

vec3 ddgi_grid_position(uvec3 g) { return ddgi.origin.xyz + vec3(g) * ddgi.origin.w; }

// Where probe p is this frame: its grid position moved by relocation.
vec3 ddgi_probe_position(uint p) {
  vec3 x = ddgi_grid_position(ddgi_probe_coords(p));
  return ddgi.switches.y != 0u ? x + ddgi_probes[p].offset.xyz : x;
}

bool ddgi_probe_active(uint p) {
  return ddgi.switches.z == 0u || ddgi_probes[p].offset.w == GIQ_DDGI_ACTIVE;
}

// Point i of n on the spherical Fibonacci spiral (Keinert et al. 2015, "Spherical Fibonacci
// Mapping", equation 2): n nearly evenly spaced directions.
vec3 spherical_fibonacci(float i, float n) {
  const float golden = 1.6180339887498949;
  float phi = 2.0 * PI * fract(i * (golden - 1.0));
  float cos_theta = 1.0 - (2.0 * i + 1.0) / n;
  float sin_theta = sqrt(clamp(1.0 - cos_theta * cos_theta, 0.0, 1.0));
  return vec3(cos(phi) * sin_theta, sin(phi) * sin_theta, cos_theta);
}

// Direction of fixed ray r (< GIQ_DDGI_FIXED_RAYS): its own unrotated spiral, the same every frame.
vec3 ddgi_fixed_ray_direction(uint r) { return spherical_fibonacci(float(r), float(GIQ_DDGI_FIXED_RAYS)); }

// Direction of ray r of every probe: the fixed rays as above, the blended ones on a spiral
// turned by this frame's rotation (rows r0, r1, r2).
vec3 ddgi_ray_direction(uint r, vec4 rotation[3]) {
  uint rays = ddgi.tiles.w;
  if (r < GIQ_DDGI_FIXED_RAYS) return ddgi_fixed_ray_direction(r);
  vec3 d = spherical_fibonacci(float(r - GIQ_DDGI_FIXED_RAYS), float(rays - GIQ_DDGI_FIXED_RAYS));
  return vec3(dot(rotation[0].xyz, d), dot(rotation[1].xyz, d), dot(rotation[2].xyz, d));
}

#ifndef GIQ_DDGI_NO_SAMPLERS
// Irradiance arriving at x on a surface of unit normal n, seen along the unit direction `view`
// (from the eye or the probe towards x): the 8 probes of the cell around the biased point,
// weighted by trilinear interpolation, by the wrap-shaded direction to the probe and by the
// Chebyshev bound on the probe seeing the point (Majercik et al. 2019's
// query), in the perceptual space the papers interpolate in (sqrt of linear irradiance when
// gamma = 5: the stored gamma halved), then squared back.
vec3 ddgi_irradiance_at(vec3 x, vec3 n, vec3 view) {
  float spacing = ddgi.origin.w;
  // Normal and view bias (Majercik et al. 2021): the point moves off the surface
  // and towards the viewer, away from the distance the probes saw the surface at.
  vec3 biased = x + n * ddgi.bias.x - view * ddgi.bias.y;
  ivec3 last = ivec3(ddgi.counts.xyz) - 1;
  vec3 rel = (biased - ddgi.origin.xyz) / spacing;
  ivec3 base = clamp(ivec3(floor(rel)), ivec3(0), max(last - 1, ivec3(0)));
  vec3 alpha = clamp(rel - vec3(base), 0.0, 1.0);
  float exponent = 0.5 * ddgi.bias.w;
  vec3 sum = vec3(0.0);
  float weights = 0.0;
  for (uint i = 0u; i < 8u; ++i) {
    ivec3 offset = ivec3(i & 1u, (i >> 1) & 1u, (i >> 2) & 1u);
    ivec3 g = min(base + offset, last);
    uint p = ddgi_probe_index(uvec3(g));
    if (!ddgi_probe_active(p)) continue;
    vec3 probe = ddgi_probe_position(p);
    vec3 to_probe = probe - x;
    float to_probe_len = length(to_probe);
    vec3 dir_to_probe = to_probe_len > 0.0 ? to_probe / to_probe_len : n;
    vec3 biased_to_probe = probe - biased;
    float r = length(biased_to_probe);
    vec3 probe_to_point = r > 0.0 ? -biased_to_probe / r : -n;
    vec3 tri = mix(1.0 - alpha, alpha, vec3(offset));
    float trilinear = max(0.001, tri.x * tri.y * tri.z);
    // Smooth backface test: probes behind the surface count less, but never zero, so that a
    // point whose probes all lie behind it still gets light.
    float wrap = (dot(dir_to_probe, n) + 1.0) * 0.5;
    float w = wrap * wrap + 0.2;
    if (ddgi.switches.x != 0u) {
      // Chebyshev's one-sided inequality on the distance moments the probe saw towards the
      // point: the probability that the point is not occluded from the probe.
      vec2 moments = texture(ddgi_distance, oct_atlas_uv(p, probe_to_point, ddgi.tiles.z, ddgi.tiles.x, ddgi.atlas.zw)).xy;
      float mean = moments.x;
      float variance = abs(mean * mean - moments.y);
      float visibility = 1.0;
      if (r > mean) {
        float d = r - mean;
        visibility = variance / (variance + d * d);
        visibility = visibility * visibility * visibility;  // sharpen (the papers' cube)
      }
      w *= max(0.05, visibility);
    }
    w = max(1e-6, w);
    // Crush weights below 0.2 (the papers' threshold): near-zero visibility dims a probe further,
    // so light from a probe that sees the point only barely does not bleed through.
    const float crush = 0.2;
    if (w < crush) w *= w * w / (crush * crush);
    w *= trilinear;
    vec3 e = texture(ddgi_irradiance, oct_atlas_uv(p, n, ddgi.tiles.y, ddgi.tiles.x, ddgi.atlas.xy)).rgb;
    sum += w * pow(max(e, vec3(0.0)), vec3(exponent));
    weights += w;
  }
  if (!(weights > 0.0)) return vec3(0.0);
  vec3 e = sum / weights;
  return e * e;
}
#endif

#endif
