#version 460
// Voxel direct lighting (Afanasev 2021 ch. IV and its VoxelConeTracingVoxelization.hlsl: albedo x
// shadowed direct light; Turánszki 2017 part 1: diffuse part of the main lighting model only).
// Each voxel that voxelize.comp marked holds the index of one triangle overlapping it; this
// pass replaces it by the radiance that triangle's surface reflects, at the point of the
// triangle nearest the voxel centre: (diffuse BRDF) x irradiance, stored isotropically with
// opacity 1. Emission is not stored: the shared direct pass already shows the emitters, and
// the indirect layer holds only light that has bounced at least once.
// Shadows are BVH shadow rays, not shadow maps: the sun's cascades cover only the camera's
// frustum while voxels fill the whole scene, and only surface voxels (a few percent of the
// grid) run this code.
// With more than one bounce the pass runs again after the mips are built, and each voxel adds
// the light its surface receives through the diffuse cones from those mips (Turánszki 2017, part 1:
// "we can dispatch additional cone tracing compute shader passes for the whole structure").
// Those cones read only the anisotropic chains, never the base level this pass writes.
// Light types: punctual lights exactly (glTF units); an emissive mesh as one cosine-weighted
// emitter at its representative point (scenes::AreaLight), E = P.cos_e cos_r / (d^2 + A/pi)
// with P = sum L A (the + A/pi keeps the irradiance of a disc of area A on its axis finite and
// exact; far away it is the point form), shadowed by one ray to that point.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/bvh.glsl"
#include "shaders/brdf.glsl"
#include "shaders/surface.glsl"
#include "shaders/lights.glsl"
#include "shaders/closest_point.glsl"
#include "techniques/vct/vct_shared.h"
#include "techniques/vct/voxel.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = GIQ_SCENE_BINDING_COUNT + 0, r32ui) uniform uimage3D voxels;
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 1) readonly buffer Emitters { VctEmitter emitters[]; };
layout(binding = GIQ_SCENE_BINDING_COUNT + 2) uniform sampler3D chain_px;
layout(binding = GIQ_SCENE_BINDING_COUNT + 3) uniform sampler3D chain_nx;
layout(binding = GIQ_SCENE_BINDING_COUNT + 4) uniform sampler3D chain_py;
layout(binding = GIQ_SCENE_BINDING_COUNT + 5) uniform sampler3D chain_ny;
layout(binding = GIQ_SCENE_BINDING_COUNT + 6) uniform sampler3D chain_pz;
layout(binding = GIQ_SCENE_BINDING_COUNT + 7) uniform sampler3D chain_nz;
layout(push_constant) uniform Push { VctLightPush pc; };

#define GIQ_VCT_CHAINS_ONLY
#define VCT_GRID pc.grid
#define VCT_MAX_DISTANCE pc.cone.max_distance
#define VCT_STEP_FACTOR pc.cone.step_factor
#define VCT_AO_FALLOFF 0.0
#define VCT_START (pc.cone.start_offset * pc.grid.origin.w)
#define VCT_GUARD pc.cone.guard
#include "techniques/vct/cone.glsl"

// Visibility from p (on a surface of geometric normal ng) towards wi up to dist.
float visible(vec3 p, vec3 ng, vec3 wi, float dist) {
  vec3 o = p + ng * (dot(ng, wi) >= 0.0 ? pc.ray_offset : -pc.ray_offset);
  return trace_ray(o, wi, dist, true).triangle == 0xffffffffu ? 1.0 : 0.0;
}

void main() {
  ivec3 cell = ivec3(gl_GlobalInvocationID);
  int res = int(pc.grid.resolution);
  if (any(greaterThanEqual(cell, ivec3(res)))) return;
  uint tri = imageLoad(voxels, cell).x;
  if (tri == GIQ_VCT_EMPTY) {
    imageStore(voxels, cell, uvec4(0u));
    return;
  }
  vec3 a, b, c;
  triangle_vertices(tri, a, b, c);
  vec3 centre = pc.grid.origin.xyz + (vec3(cell) + 0.5) * pc.grid.origin.w;
  vec3 p = closest_on_triangle(centre, a, b, c);
  vec3 ng = normalize(cross(b - a, c - a));
  GpuMaterial mat = scene_materials[scene_triangles[tri].v.w];
  bool two_sided = mat.params.w != 0.0;
  // The diffuse BRDF at normal incidence (its Fresnel weight varies little with angle), with
  // the material's textures at p.
  vec2 bary = vec2(0.0);
#ifdef GIQ_SURFACE_TEXTURES
  bary = plane_barycentrics(p, a, b, c);
#endif
  Surface s = hit_material(tri, bary.x, bary.y, ng);
  vec3 fd, fs;
  brdf_parts(s, ng, ng, fd, fs);

  vec3 e = vec3(0.0);
  for (uint i = 0u; i < pc.light_count; ++i) {
    vec3 wi;
    float dist;
    vec3 li = punctual_incident(scene_lights[i], p, wi, dist);
    float cos_r = dot(ng, wi);
    if (two_sided) cos_r = abs(cos_r);
    if (cos_r <= 0.0 || all(equal(li, vec3(0.0)))) continue;
    e += li * cos_r * visible(p, ng, wi, dist);
  }
  for (uint i = 0u; i < pc.emitter_count; ++i) {
    VctEmitter em = emitters[i];
    vec3 to = em.position.xyz - p;
    float d2 = dot(to, to);
    if (!(d2 > 0.0)) continue;
    float dist = sqrt(d2);
    vec3 wi = to / dist;
    float cos_e = dot(em.normal.xyz, -wi);
    if (em.normal.w == 1.0) cos_e = abs(cos_e);
    if (em.normal.w == 2.0) cos_e = 0.25;
    float cos_r = dot(ng, wi);
    if (two_sided) cos_r = abs(cos_r);
    if (cos_e <= 0.0 || cos_r <= 0.0) continue;
    // Stop short of the emitter so that its own triangles do not shadow it.
    float reach = (dist - em.position.w) * 0.999;
    if (reach <= 0.0) continue;  // inside a closed emitter's extent
    e += em.power.rgb * (cos_e * cos_r / (d2 + em.power.w / PI)) * visible(p, ng, wi, reach);
  }
  vec3 stored = fd * e * pc.scale;
  if (pc.add_bounce != 0u) {
    // The surface's side that faces the voxel centre (a one-sided surface: its front).
    vec3 n = two_sided && dot(centre - p, ng) < 0.0 ? -ng : ng;
    vec3 start = p + n * (pc.cone.start_offset * pc.grid.origin.w);
    uint cones = pc.cone.count;
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < cones; ++i) {
      vec3 dir;
      float weight, occ;
      diffuse_cone(i, cones, n, dir, weight);
      sum += weight * trace_cone(start, dir, pc.cone.aperture, occ).rgb;
    }
    stored += fd * PI * sum;  // already in stored units
  }
  imageStore(voxels, cell, uvec4(pack_voxel(vec4(stored, 1.0))));
}
