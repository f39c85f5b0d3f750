#version 460
// hybrid, the samples (Kim-Chan 2022, section 3.1): at each G-buffer point, one shadow ray
// to one light source chosen at random (next-event estimation with GIQ_ONE_LIGHT,
// shaders/path.glsl) and one bounce ray from the diffuse or the GGX lobe, chosen by the
// specular weight (brdf_sample), followed for max_bounces surfaces with Russian roulette: the
// same paths as `pt` from the first hit on, so that their mean converges to the reference.
// Outputs per pixel, the mean of `samples` such paths: raw direct light (with the emission
// and background the camera sees), raw indirect light, that emission and background alone
// (svgf.h does not filter it), and the albedo that SVGF demodulates by.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/bvh.glsl"
#include "shaders/brdf.glsl"
#include "shaders/surface.glsl"
#include "shaders/camera.glsl"
#include "shaders/lights.glsl"
#include "shaders/environment.glsl"
#include "shaders/path.glsl"
#include "techniques/hybrid/hybrid_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

#include "passes/receiver.glsl"
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 0, rgba32f) uniform writeonly image2D out_direct;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 1, rgba32f) uniform writeonly image2D out_indirect;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 2, rgba32f) uniform writeonly image2D out_unfiltered;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 3, rgba32f) uniform writeonly image2D out_albedo;

layout(push_constant) uniform Push { HybridSamplePush pc; };

// What SVGF divides the light by: the BRDF's reflectance at normal incidence, diffuse plus
// specular (the metal's colour for metals), so that texture detail stays out of the filter.
vec3 demodulation_albedo(Surface s) {
#ifdef GIQ_SPECULAR
  return s.base_color * (1.0 - s.metallic) + mix(dielectric_f0(s), s.base_color, s.metallic);
#else
  return s.base_color * (1.0 - s.metallic);
#endif
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), pc.size))) return;
  Receiver r = load_receiver(px);
  vec3 seen = vec3(0.0), direct = vec3(0.0), indirect = vec3(0.0), albedo = vec3(0.0);
  if (!r.hit) {
    // The camera sees the environment directly, in the direction of the pixel's centre.
    seen = environment_radiance(pc.environment, camera_ray_direction(pc.camera, vec2(px) + 0.5, vec2(pc.size)));
  } else if (r.lit) {  // the back of a one-sided material is black
    GpuMaterial mat = scene_materials[r.material];
    if (mat.emissive.w != 0.0) seen = emission_at(mat, r.tri, r.bary.x, r.bary.y, r.footprint);
    Surface s = receiver_surface(r);
    albedo = demodulation_albedo(s);
    vec3 wo = camera_to_eye(pc.camera, r.x);
    // The geometric normal on the viewer's side: light from below it would leak through.
    vec3 ng = receiver_geometric_normal(r);
    vec3 p_off = offset_ray(r.x, ng);
    PathParams params = PathParams(pc.environment, pc.max_bounces, pc.light_count, pc.emissive_count);
    for (uint k = 0u; k < pc.samples; ++k) {
      Rng rng = rng_init(uvec2(px), pc.first_sample + k, pc.seed);
      PathState st = path_start();
      path_add(st, 1u, next_event(params, r.x, p_off, ng, r.n, s, wo, rng));
      vec3 wi;
      if (path_scatter(st, 0u, s, wo, ng, r.n, rng, wi))
        path_trace(params, st, 1u, p_off, wi, rng);
      // A non-finite sample can only come from a degenerate configuration: dropped (black).
      if (!all(lessThan(abs(st.direct + st.indirect), vec3(3.0e38)))) continue;
      direct += st.direct;
      indirect += st.indirect;
    }
    direct /= float(pc.samples);
    indirect /= float(pc.samples);
  }
  imageStore(out_direct, px, vec4(seen + direct, 1.0));
  imageStore(out_indirect, px, vec4(indirect, 1.0));
  imageStore(out_unfiltered, px, vec4(seen, 1.0));
  imageStore(out_albedo, px, vec4(albedo, 1.0));
}
