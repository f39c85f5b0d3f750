#version 460
// SVGF, step 1 (Schied et al. 2017, section 4.1): the raw signals are demodulated by the
// albedo, each pixel's history is fetched where its surface was in the previous frame
// (bilinear taps, each kept only where the object, the depth and the normal agree; a 3x3
// search when none is kept) and blended with exponential moving averages of the colour and of
// the first two moments of its luminance; the variance of the luminance follows from the
// moments. Both signals (direct and indirect light) share the surface tests and the history
// length. Also writes this frame's surface for the next frame and the later passes.
#extension GL_GOOGLE_include_directive : require

#include "techniques/hybrid/svgf.glsl"
#include "techniques/hybrid/svgf_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0, rgba32f) uniform readonly image2D gb_position;
layout(binding = 1, rgba32f) uniform readonly image2D gb_normal;
layout(binding = 2, rgba32ui) uniform readonly uimage2D gb_ids;
layout(binding = 3, rgba32f) uniform readonly image2D gb_motion;
layout(binding = 4, rgba32f) uniform readonly image2D raw_direct;
layout(binding = 5, rgba32f) uniform readonly image2D raw_indirect;
layout(binding = 6, rgba32f) uniform readonly image2D unfiltered;
layout(binding = 7, rgba32f) uniform readonly image2D albedo;
layout(binding = 8, rgba32f) uniform writeonly image2D surface_out;
layout(binding = 9, r32ui) uniform writeonly uimage2D object_out;
layout(binding = 10, rgba32f) uniform readonly image2D surface_prev;
layout(binding = 11, r32ui) uniform readonly uimage2D object_prev;
layout(binding = 12, rgba32f) uniform readonly image2D history_direct;
layout(binding = 13, rgba32f) uniform readonly image2D history_indirect;
layout(binding = 14, rgba32f) uniform readonly image2D moments_prev;
layout(binding = 15, rgba32f) uniform writeonly image2D moments_out;
layout(binding = 16, r32f) uniform readonly image2D length_prev;
layout(binding = 17, r32f) uniform writeonly image2D length_out;
layout(binding = 18, rgba32f) uniform writeonly image2D integrated_direct;
layout(binding = 19, rgba32f) uniform writeonly image2D integrated_indirect;

layout(push_constant) uniform Push { SvgfReprojectPush pc; };

// Falcor's SVGFPass tolerances, made independent of the scene's units: a previous sample is
// the same surface when its depth differs by less than kDepthTolerance pixel-to-pixel depth
// changes plus kRelativeDepth of the depth, and its normal by less than kNormalTolerance
// (Euclidean distance of unit normals: about 9 degrees).
const float kDepthTolerance = 10.0;
const float kRelativeDepth = 0.01;
const float kNormalTolerance = 0.16;

struct History {
  vec3 direct;
  vec3 indirect;
  vec4 moments;  // direct (mean, mean square), indirect (mean, mean square) of the luminance
  float frames;
};

bool same_surface(ivec2 q, uint object, float z_prev_camera, float dz, vec3 n) {
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(uvec2(q), pc.size))) return false;
  if (imageLoad(object_prev, q).x != object) return false;
  SvgfSurface s = svgf_surface(imageLoad(surface_prev, q));
  if (abs(s.z - z_prev_camera) > kDepthTolerance * dz + kRelativeDepth * z_prev_camera) return false;
  return distance(s.n, n) <= kNormalTolerance;
}

void add_tap(inout History h, ivec2 q, float w) {
  h.direct += w * imageLoad(history_direct, q).rgb;
  h.indirect += w * imageLoad(history_indirect, q).rgb;
  h.moments += w * imageLoad(moments_prev, q);
  h.frames += w * imageLoad(length_prev, q).x;
}

// The previous frame's history at the place p's surface was, or frames = 0.
History reproject(ivec2 px, uint object, vec3 x, float dz, vec3 n) {
  History h = History(vec3(0.0), vec3(0.0), vec4(0.0), 0.0);
  vec4 motion = imageLoad(gb_motion, px);
  if (pc.history == 0u || motion.w == 0.0) return h;
  // The depth this point had in the previous camera (exact for static geometry).
  float z = dot(x - pc.previous_eye.xyz, pc.previous_forward.xyz);
  vec2 pos = vec2(px) + motion.xy;  // in pixel indices: centres at integers
  ivec2 base = ivec2(floor(pos));
  vec2 f = pos - vec2(base);
  float sum = 0.0;
  for (int i = 0; i < 4; ++i) {
    ivec2 o = ivec2(i & 1, i >> 1);
    float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
    if (w > 0.0 && same_surface(base + o, object, z, dz, n)) {
      add_tap(h, base + o, w);
      sum += w;
    }
  }
  if (sum < 0.01) {  // no bilinear tap is the same surface: any of the 3x3 around
    h = History(vec3(0.0), vec3(0.0), vec4(0.0), 0.0);
    sum = 0.0;
    ivec2 c = ivec2(floor(pos + 0.5));
    for (int j = -1; j <= 1; ++j)
      for (int i = -1; i <= 1; ++i)
        if (same_surface(c + ivec2(i, j), object, z, dz, n)) {
          add_tap(h, c + ivec2(i, j), 1.0);
          sum += 1.0;
        }
  }
  if (sum <= 0.0) return History(vec3(0.0), vec3(0.0), vec4(0.0), 0.0);
  h.direct /= sum;
  h.indirect /= sum;
  h.moments /= sum;
  h.frames /= sum;
  return h;
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), pc.size))) return;
  uvec4 ids = imageLoad(gb_ids, px);
  vec4 position = imageLoad(gb_position, px);
  vec4 normal = imageLoad(gb_normal, px);
  vec3 a = imageLoad(albedo, px).rgb;
  bool surface = ids.x != 0u && position.w > 0.0 && any(greaterThan(a, vec3(0.0)));
  if (!surface) {  // nothing to filter: the unfiltered layer carries the pixel
    imageStore(surface_out, px, vec4(0.0));
    imageStore(object_out, px, uvec4(0u));
    imageStore(moments_out, px, vec4(0.0));
    imageStore(length_out, px, vec4(0.0));
    imageStore(integrated_direct, px, vec4(0.0));
    imageStore(integrated_indirect, px, vec4(0.0));
    return;
  }
  vec3 x = position.xyz, n = normal.xyz;
  float z = dot(x - pc.eye.xyz, pc.forward.xyz);
  float nf = dot(n, pc.forward.xyz);
  // The depth bound is floored at 1e-4 of the depth, far above float rounding (6e-8), so
  // that a plane facing the camera still filters across its own pixels.
  float dz = max(min(normal.w, 1e30) * sqrt(max(0.0, 1.0 - nf * nf)), 1e-4 * z);
  uint object = ids.z + 1u;
  imageStore(surface_out, px, vec4(oct_encode(n), z, dz));
  imageStore(object_out, px, uvec4(object));

  vec3 demod = max(a, vec3(kSvgfAlbedoFloor));
  vec3 e = imageLoad(unfiltered, px).rgb;
  vec3 cd = max(imageLoad(raw_direct, px).rgb - e, vec3(0.0)) / demod;
  vec3 ci = imageLoad(raw_indirect, px).rgb / demod;
  float ld = svgf_luminance(cd), li = svgf_luminance(ci);
  vec4 moments = vec4(ld, ld * ld, li, li * li);

  History h = reproject(px, object, x, dz, n);
  bool kept = h.frames > 0.0;
  float frames = kept ? min(h.frames + 1.0, pc.history_cap) : 1.0;
  // max(alpha, 1/frames): the plain mean of the samples while there are few of them.
  float ac = kept ? max(pc.alpha_colour, 1.0 / frames) : 1.0;
  float am = kept ? max(pc.alpha_moments, 1.0 / frames) : 1.0;
  cd = mix(h.direct, cd, ac);
  ci = mix(h.indirect, ci, ac);
  moments = mix(h.moments, moments, am);
  imageStore(moments_out, px, moments);
  imageStore(length_out, px, vec4(frames));
  // The variance of the luminance from the temporal moments; svgf_variance.comp replaces it
  // with a spatial estimate while the history is short.
  imageStore(integrated_direct, px, vec4(cd, max(0.0, moments.y - moments.x * moments.x)));
  imageStore(integrated_indirect, px, vec4(ci, max(0.0, moments.w - moments.z * moments.z)));
}
