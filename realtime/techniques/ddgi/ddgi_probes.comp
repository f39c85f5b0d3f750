#version 460
// `ddgi`'s probe relocation and classification (Majercik et al. 2021; RTXGI's
// documentation, "Probe Relocation" and "Probe Classification"), one invocation per probe,
// from the frame's fixed rays (the same directions every frame, so the decisions are stable):
//   relocation: a probe whose fixed rays hit back faces more often than the threshold is
//     inside geometry and moves through the closest back face, by that distance plus half the
//     distance kept from front faces; a probe closer than that distance to a front face moves
//     away from it, towards its farthest hit, unless that lies on the same side. An offset
//     larger than 0.45 spacing on any axis is refused, so a probe stays in its cell.
//   classification: a probe inside geometry, or whose fixed rays hit no front face within the
//     cells around it (the box of one spacing around the probe), is inactive: it traces only
//     its fixed rays, keeps its atlas tiles and is left out of every irradiance query.
// It also counts each active probe's frames of history for ddgi_blend.comp.
#extension GL_GOOGLE_include_directive : require

#include "shaders/sampling.glsl"
#include "techniques/ddgi/ddgi_shared.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Volume { GpuDdgiVolume ddgi; };
layout(std430, binding = 1) buffer Probes { GpuDdgiProbe ddgi_probes[]; };
layout(std430, binding = 2) readonly buffer Rays { vec4 rays[]; };
layout(std430, binding = 3) buffer History { uint history[]; };

layout(push_constant) uniform Push { DdgiProbePush pc; };

#define GIQ_DDGI_NO_SAMPLERS
#include "techniques/ddgi/ddgi_volume.glsl"

void main() {
  uint probe = gl_GlobalInvocationID.x;
  if (probe >= ddgi.counts.w) return;
  if (ddgi_probe_active(probe)) history[probe] += 1u;
  uint base = probe * ddgi.tiles.w;
  uint backfaces = 0u;
  float closest_back = 3.0e38, closest_front = 3.0e38, farthest_front = 0.0;
  vec3 closest_back_dir = vec3(0.0), closest_front_dir = vec3(0.0), farthest_front_dir = vec3(0.0);
  bool near_surface = false;
  float spacing = ddgi.origin.w;
  for (uint r = 0u; r < GIQ_DDGI_FIXED_RAYS; ++r) {
    float t = rays[base + r].w;
    vec3 dir = ddgi_fixed_ray_direction(r);
    if (t < 0.0) {
      ++backfaces;
      if (-t < closest_back) { closest_back = -t; closest_back_dir = dir; }
      continue;
    }
    if (t < closest_front) { closest_front = t; closest_front_dir = dir; }
    if (t > farthest_front) { farthest_front = t; farthest_front_dir = dir; }
    // Where the ray leaves the box of one spacing around the probe.
    vec3 ad = max(abs(dir), vec3(1e-8));
    float exit = spacing / max(ad.x, max(ad.y, ad.z));
    if (t < exit) near_surface = true;
  }
  bool inside = float(backfaces) > pc.backface_threshold * float(GIQ_DDGI_FIXED_RAYS);
  vec4 data = ddgi_probes[probe].offset;
  if (ddgi.switches.y != 0u) {
    vec3 offset = data.xyz;
    if (inside) {
      offset += closest_back_dir * (closest_back + 0.5 * pc.min_frontface);
    } else if (closest_front < pc.min_frontface && dot(closest_front_dir, farthest_front_dir) <= 0.0) {
      offset += farthest_front_dir * min(farthest_front, pc.min_frontface);
    }
    if (all(lessThanEqual(abs(offset), vec3(pc.max_offset)))) data.xyz = offset;
  }
  if (ddgi.switches.z != 0u) data.w = !inside && near_surface ? GIQ_DDGI_ACTIVE : GIQ_DDGI_INACTIVE;
  ddgi_probes[probe].offset = data;
}
