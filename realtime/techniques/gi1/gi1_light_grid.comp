#version 460
// `gi1`: the light grid (Boissé et al. 2022, section 2.3.2), rebuilt every frame (lights move):
// a uniform grid of cubic cells over the scene's bounds, the longest axis in
// `light_grid_cells` cells, each listing the `light_grid_lights` lights (or all, if fewer)
// that deposit the most light in it. A light's deposit over a cell is its importance at the
// 8 corners averaged (the report's trilinear approximation of the volume integral, its
// Equation 1); a light that deposits nothing (behind a one-sided emitter at every corner) is
// left out. A cell's list is the top of the order (deposit descending, light index ascending
// among equals). One workgroup a cell: its 64 lanes evaluate 8 lights at 8 corners at a time
// (an area light's importance sums over its triangles, a particle stage's over its light
// tree's clusters), one lane per light keeps a list of the lights it summed, and the first
// lane merges the lists. Every sum is taken in the order one invocation going through the
// lights and corners would take, so the list is the same on every run and the same bits as
// that (which took 2.0 ms on the H200 for `dynamic`'s particles).
// The report bounds the grid by the frame's hit points; giq's scenes are rooms and courts
// whose hits fill their bounds, so the scene's bounds serve and the grid is ready before the
// rays are traced.
// Layout per cell: the count, then the light indices, most important first.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/surface.glsl"
#include "shaders/sampling.glsl"
#include "shaders/lights.glsl"
#include "shaders/environment.glsl"
#include "passes/direct_light_shared.h"
#include "techniques/gi1/gi1_shared.h"

#define GIQ_GI1_GRID_SLOTS 8u  // lights evaluated at once, each at the cell's 8 corners
layout(local_size_x = 64) in;

#include "passes/receiver.glsl"
#include "techniques/gi1/gi1_common.glsl"
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 0) readonly buffer AreaLights { GpuAreaLight area_lights[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 1) readonly buffer AreaTriangles { GpuAreaTriangle area_triangles[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 2) writeonly buffer LightGrid { uint light_grid[]; };
// The particles' light tree (DirectLightPass::particle_tree_descriptors).
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 3) readonly buffer ParticleTree { GpuBvhNode particle_tree[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 4) readonly buffer ParticleClusters { vec4 particle_clusters[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 5) readonly buffer StageRoots { uint stage_roots[]; };

#include "passes/area_light_parts.glsl"
#include "techniques/gi1/gi1_light.glsl"
#include "techniques/gi1/gi1_particle_importance.glsl"

// How much light l deposits at point c, as luminance (the grid's importance, section 2.3.2):
// a spot counts as a point light (its cone may cross a cell between its corners), an area
// light as its triangles' power towards c with the inverse-square law, no closer than
// `near` (a corner on the light), a stage of particles in the light tree by its clusters, the
// environment as pi times its mean radiance.
float gi1_light_importance(uint l, vec3 c, float near) {
  if (l < gi1.counts.x) {
    GpuLight s = scene_lights[l];
    if (int(s.position.w) == GIQ_LIGHT_DIRECTIONAL) return luminance(s.radiant.rgb);
    vec3 d = s.position.xyz - c;
    float d2 = max(dot(d, d), near * near);
    return luminance(s.radiant.rgb) * range_window(sqrt(d2), s.direction.w) / d2;
  }
  if (gi1_is_environment(l)) return PI * luminance(gi1_environment_mean());
  GpuAreaLight a = area_lights[l - gi1.counts.x];
  uint slot = uint(a.extent.w);
  if (slot > 0u && lit_particles(a) > 0u) return gi1_particle_importance(a, slot - 1u, c, near, kGi1ParticleImportanceCut);
  float sum = 0.0;
  for (uint k = 0u; k < a.range.y; ++k) {
    GpuAreaTriangle t = area_triangle(a, k);
    vec3 n2 = cross(t.b.xyz - t.a.xyz, t.c.xyz - t.a.xyz);  // twice the area along the normal
    vec3 to = c - (t.a.xyz + t.b.xyz + t.c.xyz) / 3.0;
    float d2 = max(dot(to, to), near * near);
    float cos_area = dot(n2, to) / sqrt(d2);  // cos x twice the area
    if (t.a.w != 0.0) cos_area = abs(cos_area);
    sum += luminance(t.radiance.rgb) * 0.5 * max(cos_area, 0.0) / d2;
  }
  return sum;
}

#define GIQ_GI1_MAX_CELL_LIGHTS 64u

shared float corner_value[64];
// Entry i of slot j's list at [i][j].
shared uint slot_best[GIQ_GI1_MAX_CELL_LIGHTS][GIQ_GI1_GRID_SLOTS];
shared float slot_score[GIQ_GI1_MAX_CELL_LIGHTS][GIQ_GI1_GRID_SLOTS];
shared uint slot_count[GIQ_GI1_GRID_SLOTS];

void main() {
  uvec3 n = gi1.grid_cells.xyz;
  uint cell = gl_WorkGroupID.x + gl_WorkGroupID.y * n.x * n.y, lane = gl_LocalInvocationID.x;
  uint slot = lane / 8u, k = lane % 8u;
  uvec3 c = uvec3(cell % n.x, (cell / n.x) % n.y, cell / (n.x * n.y));
  float side = gi1.grid.w;
  vec3 lo = gi1.grid.xyz + vec3(c) * side;
  vec3 corner = lo + vec3(k & 1u, (k >> 1) & 1u, k >> 2) * side;
  uint k_max = min(gi1.grid_cells.w, GIQ_GI1_MAX_CELL_LIGHTS);
  uint best[GIQ_GI1_MAX_CELL_LIGHTS];
  float score[GIQ_GI1_MAX_CELL_LIGHTS];
  uint count = 0u;
  for (uint first = 0u; first < gi1.lights.x; first += GIQ_GI1_GRID_SLOTS) {
    uint l = first + slot;
    corner_value[lane] = l < gi1.lights.x ? gi1_light_importance(l, corner, 0.5 * side) : 0.0;
    barrier();
    if (k == 0u && l < gi1.lights.x) {
      float s = 0.0;
      for (uint j = 0u; j < 8u; ++j) s += corner_value[lane + j];
      s *= 0.125;
      // Insert into the slot's list sorted by importance, highest first; the least
      // important drops out of a full list (earlier lights first among equals).
      uint at = count < k_max ? count : k_max;
      while (at > 0u && score[at - 1u] < s) --at;
      if (s > 0.0 && at < k_max) {
        for (uint i = min(count, k_max - 1u); i > at; --i) {
          best[i] = best[i - 1u];
          score[i] = score[i - 1u];
        }
        best[at] = l;
        score[at] = s;
        count = min(count + 1u, k_max);
      }
    }
    barrier();
  }
  if (k == 0u) {
    for (uint i = 0u; i < count; ++i) {
      slot_best[i][slot] = best[i];
      slot_score[i][slot] = score[i];
    }
    slot_count[slot] = count;
  }
  barrier();
  if (lane != 0u) return;
  // Merge: the cell's next light is the slots' best head, the lowest index among equal ones.
  uint head[GIQ_GI1_GRID_SLOTS];
  for (uint i = 0u; i < GIQ_GI1_GRID_SLOTS; ++i) head[i] = 0u;
  uint base = cell * (gi1.grid_cells.w + 1u), total = 0u;
  for (; total < k_max; ++total) {
    uint from = GIQ_GI1_GRID_SLOTS;
    for (uint i = 0u; i < GIQ_GI1_GRID_SLOTS; ++i) {
      if (head[i] >= slot_count[i]) continue;
      if (from == GIQ_GI1_GRID_SLOTS) {
        from = i;
        continue;
      }
      float a = slot_score[head[i]][i], b = slot_score[head[from]][from];
      if (a > b || (a == b && slot_best[head[i]][i] < slot_best[head[from]][from])) from = i;
    }
    if (from == GIQ_GI1_GRID_SLOTS) break;
    light_grid[base + 1u + total] = slot_best[head[from]][from];
    ++head[from];
  }
  light_grid[base] = total;
}
