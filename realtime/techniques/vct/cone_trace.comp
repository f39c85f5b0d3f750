#version 460
// Voxel cone tracing at the G-buffer texels (Afanasev 2021 ch. IV, VoxelConeTracingPS.hlsl; Crassin
// et al. 2011): per low-resolution pixel, `cone count` diffuse cones of aperture tan 30 deg
// around the shading normal and one specular cone along the reflection direction, each
// marched front to back through the voxel mips.
//
// Units: the voxels hold outgoing radiance, so a cone returns the radiance arriving from its
// solid angle. The diffuse cone weights are the cones' shares of the cosine-weighted
// hemisphere (the thesis's 0.25 for the 30 deg cone on the normal is exactly
// int_cap cos / pi = sin^2 30 deg; the five others share the remaining 0.75), so
// irradiance = pi sum_i w_i L_i and the outgoing diffuse radiance is f_d pi sum_i w_i L_i
// with f_d the diffuse BRDF (albedo / pi for Lambert).
//
// The thesis's table places its side cones at 60 deg from the normal in a frame where y is
// the normal, but its shader adds only their x and z parts to the normal (with weight 1, not
// 0.5), which tilts them to 40 deg; here each direction is x right + y normal + z up.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/brdf.glsl"
#include "shaders/surface.glsl"
#include "shaders/camera.glsl"
#include "techniques/vct/vct_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;
#include "passes/receiver.glsl"
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 0) uniform sampler3D base;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 1) uniform sampler3D chain_px;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 2) uniform sampler3D chain_nx;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 3) uniform sampler3D chain_py;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 4) uniform sampler3D chain_ny;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 5) uniform sampler3D chain_pz;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 6) uniform sampler3D chain_nz;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 7, rgba32f) uniform writeonly image2D out_low;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 8, rgba32f) uniform writeonly image2D out_ao;
layout(push_constant) uniform Push { VctConePush pc; };

#define VCT_GRID pc.grid
#define VCT_MAX_DISTANCE pc.cone.max_distance
#define VCT_STEP_FACTOR pc.cone.step_factor
#define VCT_AO_FALLOFF pc.cone.ao_falloff
#define VCT_START (pc.cone.start_offset * pc.grid.origin.w)
#define VCT_GUARD pc.cone.guard
#include "techniques/vct/cone.glsl"

void main() {
  ivec2 lp = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(lp), pc.low_size))) return;
  Receiver r = load_receiver(full_resolution_pixel(lp, int(pc.factor), ivec2(pc.size)));
  vec4 result = vec4(0.0);
  if (r.lit) {  // the back of a one-sided material is black
    vec3 p = r.x;
    vec3 n = r.n;
    vec3 wo = camera_to_eye(pc.eye, p);
    Surface s = receiver_surface(r);
    vec3 start = p + n * (pc.cone.start_offset * pc.grid.origin.w);

    uint cones = pc.cone.count;
    vec3 diffuse_sum = vec3(0.0);
    float occlusion_sum = 0.0;
    for (uint i = 0u; i < cones; ++i) {
      vec3 dir;
      float weight;
      diffuse_cone(i, cones, n, dir, weight);
      float occ;
      diffuse_sum += weight * trace_cone(start, dir, pc.cone.aperture, occ).rgb;
      occlusion_sum += weight * occ;
    }
    vec3 fd, fs;
    brdf_parts(s, wo, n, fd, fs);
    vec3 radiance = fd * PI * diffuse_sum;
#ifdef GIQ_SPECULAR
    // One cone along the mirror direction whose aperture follows the GGX lobe width
    // (tan of the half angle ~ alpha), at least the thesis's 5 degrees; weighted by the
    // lobe's Fresnel reflectance at the viewing angle.
    vec3 r = reflect(-wo, n);
    if (dot(r, n) > 0.0) {
      float aperture = clamp(s.alpha, 0.0875, 1.0);
      float occ;
      vec3 ls = trace_cone(start, r, aperture, occ).rgb;
      float nv = max(dot(n, wo), 0.0);
      vec3 f = (1.0 - s.metallic) * schlick(dielectric_f0(s), vec3(s.specular), nv) +
               s.metallic * schlick(s.base_color, vec3(1.0), nv);
      radiance += f * ls;
    }
#endif
    result = vec4(radiance * pc.decode_scale, occlusion_sum);
  }
  imageStore(out_low, lp, vec4(result.rgb, 1.0));
  // Ambient occlusion as a grey image for its own upsample: the share of the cosine-weighted
  // hemisphere occluded (0 = open, as where nothing was hit and the upsample writes 0).
  if (pc.ao != 0u) imageStore(out_ao, lp, vec4(vec3(result.a), 1.0));
}
