#version 460
// `ddgi`'s per-pixel lookup (Majercik et al. 2019, the irradiance query): the indirect radiance of a
// Lambertian receiver, diffuse albedo / pi x the volume's irradiance at the G-buffer point
// (ddgi_irradiance_at: 8 probes, trilinear x wrap x Chebyshev weights, normal and view bias).
// DDGI stores irradiance only: glossy reflection of indirect light is not represented.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/surface.glsl"
#include "shaders/camera.glsl"
#include "shaders/sampling.glsl"
#include "passes/rsm_albedo.glsl"
#include "techniques/ddgi/ddgi_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

#include "passes/receiver.glsl"
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 0) readonly buffer Volume { GpuDdgiVolume ddgi; };
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 1) readonly buffer Probes { GpuDdgiProbe ddgi_probes[]; };
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 2) uniform sampler2D ddgi_irradiance;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 3) uniform sampler2D ddgi_distance;
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 4, rgba32f) uniform writeonly image2D out_indirect;

layout(push_constant) uniform Push { DdgiShadePush pc; };

#include "techniques/ddgi/ddgi_volume.glsl"

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), pc.size))) return;
  Receiver r = load_receiver(px);
  vec3 radiance = vec3(0.0);
  if (r.lit) {
    vec3 view = -camera_to_eye(pc.eye, r.x);
    radiance = diffuse_albedo(receiver_surface(r)) / PI * ddgi_irradiance_at(r.x, r.n, view);
  }
  imageStore(out_indirect, px, vec4(radiance, 1.0));
}
