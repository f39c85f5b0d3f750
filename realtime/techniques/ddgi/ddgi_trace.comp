#version 460
// `ddgi`'s probe rays (Majercik et al. 2019): every active probe traces its rays
// through the shared compute BVH; each hit is shaded with the light the shared direct pass
// uses, shadowed by BVH rays (passes/hit_irradiance.glsl) since the frame's shadow maps cover
// only what the camera sees, plus the volume's own irradiance at the hit from the previous
// update (one more bounce per frame; the albedo capped below 1 keeps the loop contracting).
// The hit's own emission is left out: an emissive mesh's light reaches receivers through the
// shared direct pass (its area light), and counting it here too would add it twice. Misses
// see the environment (a map too), which the direct pass does not light surfaces with: that
// light lands in the indirect layer.
// Output per ray: radiance, and the hit distance, negative for the back of a one-sided
// surface (a probe that sees many is inside geometry).
// Inactive probes (classification) trace only their fixed rays, which need no shading.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/bvh.glsl"
#include "shaders/brdf.glsl"
#include "shaders/surface.glsl"
#include "shaders/sampling.glsl"
#include "shaders/lights.glsl"
#include "shaders/octahedron_irradiance.glsl"
#include "shaders/environment.glsl"
#include "passes/direct_light_shared.h"
#include "passes/rsm_albedo.glsl"
#include "techniques/ddgi/ddgi_shared.h"

layout(local_size_x = 64) in;

layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 0) readonly buffer Volume { GpuDdgiVolume ddgi; };
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 1) readonly buffer Probes { GpuDdgiProbe ddgi_probes[]; };
layout(binding = GIQ_SCENE_BINDING_COUNT + 2) uniform sampler2D ddgi_irradiance;
layout(binding = GIQ_SCENE_BINDING_COUNT + 3) uniform sampler2D ddgi_distance;
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 4) readonly buffer AreaLights { GpuAreaLight area_lights[]; };
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 5) readonly buffer AreaTriangles { GpuAreaTriangle area_triangles[]; };
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 6) writeonly buffer Rays { vec4 rays[]; };

layout(push_constant) uniform Push { DdgiTracePush pc; };

#include "techniques/ddgi/ddgi_volume.glsl"
#include "passes/area_light_parts.glsl"
#include "passes/hit_irradiance.glsl"

void main() {
  uint ray = gl_GlobalInvocationID.x;
  uint probe = gl_WorkGroupID.y + gl_WorkGroupID.z * gl_NumWorkGroups.y;
  uint count = ddgi.tiles.w;
  if (ray >= count || probe >= ddgi.counts.w) return;
  uint slot = probe * count + ray;
  bool fixed_ray = ray < GIQ_DDGI_FIXED_RAYS;
  if (!fixed_ray && !ddgi_probe_active(probe)) return;  // its blend is skipped too
  vec3 dir = ddgi_ray_direction(ray, pc.rotation);
  vec3 org = ddgi_probe_position(probe);
  RayHit hit = trace_ray(org, dir, 1e30, false);
  if (hit.triangle == 0xffffffffu) {
    rays[slot] = vec4(environment_radiance(pc.environment, dir), 3.0e38);
    return;
  }
  HitNormals hn = hit_normals(hit.triangle, hit.u, hit.v, dir);
  if (hn.black) {  // the back of a one-sided surface
    rays[slot] = vec4(0.0, 0.0, 0.0, -hit.t);
    return;
  }
  if (fixed_ray) {  // relocation and classification read only the distance
    rays[slot] = vec4(0.0, 0.0, 0.0, hit.t);
    return;
  }
  vec3 a, b, c;
  triangle_vertices(hit.triangle, a, b, c);
  vec3 p = a + hit.u * (b - a) + hit.v * (c - a);
  Surface s = hit_material(hit.triangle, hit.u, hit.v, hn.ns);
  vec3 albedo = diffuse_albedo(s);
  vec3 radiance = albedo / PI * hit_irradiance(p, hn.ng, hn.ns, pc.light_count, pc.area_light_count);
  if (pc.feedback != 0u)
    radiance += min(albedo, vec3(pc.albedo_cap)) / PI * ddgi_irradiance_at(p, hn.ns, dir);
  // A non-finite sample would poison the probe's history for good; it can only come from a
  // degenerate configuration and is dropped.
  if (!all(lessThan(abs(radiance), vec3(3.0e38)))) radiance = vec3(0.0);
  rays[slot] = vec4(radiance, hit.t);
}
