#version 460
// `gi1`: the near field (Boissé et al. 2022, section 3): the occlusion and the light of the
// surfaces within a short screen radius of each pixel, which the probes, 8 pixels apart, are
// too sparse to resolve. Horizon-based (Jimenez et al. 2016, "Practical Real-Time Strategies
// for Accurate Indirect Occlusion", GTAO), one slice per pixel and frame (section 3.2: the
// denoiser's temporal loop averages the slices), `near.y` steps on each side of it out to
// `near.x` pixels, no further than that many pixels' world size at the pixel's depth.
//
// Along each side of the slice the horizon is the highest angle a sample has reached; a sample
// that raises it covers the sector between the old and the new horizon, and that sector's
// share of the slice's cosine-weighted integral (GTAO's inner integral) receives the light
// leaving the sample (Mayaux 2018): its direct light less its emission (emitters reach
// receivers as direct light already), plus, with the feedback, albedo x the indirect
// irradiance this technique found there last frame (gi1_feedback.glsl). Sharing of the slice's
// integral rather than the integral itself (which depends on the slice for a tilted normal) is
// what is written, so a pixel with nothing above its tangent plane has visibility exactly 1 and
// its bent normal is its normal: the far field is then what it was without the near field.
//
// Output: out_near rgb the near field's irradiance, w the visible share of the cosine lobe;
// out_bent xyz the bent normal, the centre of the visible arc turned within the slice from the
// normal. gi1_interpolate.comp evaluates the probes' spherical harmonics over the cone about the
// bent normal that holds the visible share (section 3.1) and adds the near field.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/brdf.glsl"
#include "shaders/surface.glsl"
#include "shaders/sampling.glsl"
#include "shaders/camera.glsl"
#include "passes/rsm_albedo.glsl"
#include "techniques/gi1/gi1_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

#include "passes/receiver.glsl"
#include "techniques/gi1/gi1_common.glsl"
// The shared direct pass's output: the light leaving each pixel's surface towards the camera.
layout(binding = GIQ_GI1_BINDING_COUNT + 0, rgba32f) uniform readonly image2D direct_light;
layout(binding = GIQ_GI1_BINDING_COUNT + 1, rgba32f) uniform readonly image2D previous_irradiance;
layout(binding = GIQ_GI1_BINDING_COUNT + 2, rgba32f) uniform writeonly image2D out_near;
layout(binding = GIQ_GI1_BINDING_COUNT + 3, rgba16f) uniform writeonly image2D out_bent;

#include "techniques/gi1/gi1_probe.glsl"
#include "techniques/gi1/gi1_feedback.glsl"

// The slice's cosine-weighted integral from the view direction to angle theta within it, up to
// a constant (GTAO: the antiderivative of sin(theta) cos(theta - gamma), gamma the normal's
// angle in the slice). The integral over [a, b] on either side of the view direction is
// slice_integral(b) - slice_integral(a) on the positive side, slice_integral(a) -
// slice_integral(b) on the negative one.
float slice_integral(float theta, float gamma) { return -0.25 * cos(2.0 * theta - gamma) + 0.5 * theta * sin(gamma); }

// The light leaving an occluder towards the receiver, as its Lambertian part (see above).
vec3 occluder_radiance(Receiver q, ivec2 px) {
  vec3 l = imageLoad(direct_light, px).rgb;
  GpuMaterial mat = scene_materials[q.material];
  if (mat.emissive.w != 0.0) l -= emission_at(mat, q.tri, q.bary.x, q.bary.y, q.footprint);
  l = max(l, vec3(0.0));
  if (gi1_feedback_on()) l += min(diffuse_albedo(receiver_surface(q)), vec3(gi1.params.x)) / PI * feedback_irradiance(q.x);
  return l;
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), gi1.size.xy))) return;
  Receiver r = load_receiver(px);
  vec3 near = vec3(0.0), bent = r.n;
  float visible = 1.0;
  vec3 v = r.lit ? camera_to_eye(gi1.camera, r.x) : vec3(0.0);
  Rng rng = rng_init(uvec2(px), gi1.jitter.z, gi1_stream(gi1, 4u));
  float phi = PI * rng_next(rng), jitter = rng_next(rng);
  vec2 d = vec2(cos(phi), sin(phi));
  // The slice: the plane through the view direction and the screen direction d (image y runs
  // down); `axis` is its direction perpendicular to v on d's side, o its normal.
  vec3 axis = gi1.camera.right.xyz * d.x - gi1.camera.up.xyz * d.y;
  axis -= v * dot(axis, v);
  vec3 o = cross(axis, v);
  vec3 np = r.n - dot(r.n, o) * o / max(dot(o, o), 1e-30);
  if (r.lit && dot(axis, axis) > 1e-12 && dot(np, np) > 1e-12) {
    axis = normalize(axis);
    o = normalize(o);
    // The normal's angle in the slice, from v towards axis: within +-pi/2, the normal being on
    // the viewer's side.
    float gamma = atan(dot(np, axis), dot(np, v));
    float radius_px = gi1.near.x;
    float radius = radius_px * gi1_pixel_size(gi1, gi1_view_depth(gi1.camera, r.x));
    uint steps = uint(gi1.near.y);
    vec3 m = max(abs(r.x), abs(gi1.camera.position.xyz));
    float lift = max(m.x, max(m.y, m.z)) * (1.0 / 65536.0);
    float horizon[2];
    bool raised = false;
    for (int side = 0; side < 2; ++side) {
      float sgn = side == 0 ? 1.0 : -1.0;
      horizon[side] = gamma + sgn * 0.5 * PI;  // the tangent plane
      for (uint k = 0u; k < steps; ++k) {
        float t = 1.0 + (radius_px - 1.0) * (float(k) + jitter) / float(steps);
        ivec2 qp = ivec2(floor(vec2(px) + 0.5 + sgn * t * d));
        if (qp == px || any(lessThan(qp, ivec2(0))) || any(greaterThanEqual(qp, ivec2(gi1.size.xy)))) continue;
        if (imageLoad(gb_ids, qp).x == 0u) continue;  // the sky: no occluder
        vec3 w = imageLoad(gb_position, qp).xyz - r.x;
        float dist = length(w);
        // Only what lies above the tangent plane by more than the G-buffer points' error (as
        // receiver_ray_origin's) occludes: a plane must not shadow itself.
        if (!(dist > 0.0) || dist > radius || dot(w, r.n) <= lift) continue;
        float theta = sgn * acos(clamp(dot(w, v) / dist, -1.0, 1.0));
        if (sgn * theta >= sgn * horizon[side]) continue;  // not above the horizon so far
        // The sector from the new horizon to the old one receives the sample's light.
        float sector = slice_integral(horizon[side], gamma) - slice_integral(theta, gamma);
        // The occluder's material only where it raises the horizon (textures cost).
        Receiver q = load_receiver(qp);
        if (q.lit) near += abs(sector) * occluder_radiance(q, qp);
        horizon[side] = theta;
        raised = true;
      }
    }
    if (raised) {
      float f0 = slice_integral(0.0, gamma);
      float total = slice_integral(gamma + 0.5 * PI, gamma) + slice_integral(gamma - 0.5 * PI, gamma) - 2.0 * f0;
      float seen = slice_integral(horizon[0], gamma) + slice_integral(horizon[1], gamma) - 2.0 * f0;
      visible = clamp(seen / total, 0.0, 1.0);
      near *= PI / total;
      // The visible arc's centre, the normal turned to it within the slice.
      float beta = 0.5 * (horizon[0] + horizon[1]);
      bent = normalize(dot(r.n, o) * o + length(np) * (cos(beta) * v + sin(beta) * axis));
    }
  }
  imageStore(out_near, px, vec4(near, visible));
  imageStore(out_bent, px, vec4(bent, 0.0));
}
