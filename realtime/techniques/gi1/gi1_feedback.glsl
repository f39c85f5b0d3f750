// `gi1`'s radiance feedback (Boissé et al. 2022, section 2.2.4): the indirect irradiance this
// technique found at a point last frame, where the point was on screen and last frame's pixel
// showed it (within a screen cell of its depth), else 0. For the probe rays' hits
// (gi1_trace.comp) and the near field's occluders (gi1_near_field.comp). The includer binds
// last frame's irradiance (gi1_denoise_temporal.comp: rgb, w the surface's view depth, -1
// none) as `previous_irradiance`; needs shaders/camera.glsl and gi1_probe.glsl.
#ifndef GIQ_GI1_FEEDBACK_GLSL
#define GIQ_GI1_FEEDBACK_GLSL

vec3 feedback_irradiance(vec3 p) {
  vec3 q = camera_project(gi1.previous, p, vec2(gi1.size.xy));
  if (!(q.z > 0.0) || any(lessThan(q.xy, vec2(0.0))) || any(greaterThanEqual(q.xy, vec2(gi1.size.xy))))
    return vec3(0.0);
  vec4 e = imageLoad(previous_irradiance, ivec2(q.xy));
  return gi1_seen_last_frame(gi1, e.w, q.z, 1.0) ? e.rgb : vec3(0.0);
}

// Whether this frame adds the feedback: the switch is on and last frame exists.
bool gi1_feedback_on() {
  return (gi1.counts.w & (GIQ_GI1_FEEDBACK | GIQ_GI1_HISTORY)) == (GIQ_GI1_FEEDBACK | GIQ_GI1_HISTORY);
}

#endif
