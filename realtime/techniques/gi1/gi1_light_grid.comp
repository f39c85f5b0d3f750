#version 460
// `gi1`: the light grid (Boissé et al. 2022, section 2.3.2), rebuilt every frame (lights move):
// a uniform grid of cubic cells over the scene's bounds, the longest axis in
// `light_grid_cells` cells, each listing the `light_grid_lights` lights (or all, if fewer)
// that deposit the most light in it. A light's deposit over a cell is its importance at the
// 8 corners averaged (the report's trilinear approximation of the volume integral, its
// Equation 1); a light that deposits nothing (behind a one-sided emitter at every corner) is
// left out. One invocation per cell, the lights in order: the same list on every run.
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

layout(local_size_x = 64) in;

#include "passes/receiver.glsl"
#include "techniques/gi1/gi1_common.glsl"
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 0) readonly buffer AreaLights { GpuAreaLight area_lights[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 1) readonly buffer AreaTriangles { GpuAreaTriangle area_triangles[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 2) writeonly buffer LightGrid { uint light_grid[]; };

#include "techniques/gi1/gi1_light.glsl"

#define GIQ_GI1_MAX_CELL_LIGHTS 64u

void main() {
  uvec3 n = gi1.grid_cells.xyz;
  uint cell = gl_GlobalInvocationID.x;
  if (cell >= n.x * n.y * n.z) return;
  uvec3 c = uvec3(cell % n.x, (cell / n.x) % n.y, cell / (n.x * n.y));
  float side = gi1.grid.w;
  vec3 lo = gi1.grid.xyz + vec3(c) * side;
  uint k_max = min(gi1.grid_cells.w, GIQ_GI1_MAX_CELL_LIGHTS);
  uint best[GIQ_GI1_MAX_CELL_LIGHTS];
  float score[GIQ_GI1_MAX_CELL_LIGHTS];
  uint count = 0u;
  for (uint l = 0u; l < gi1.lights.x; ++l) {
    float s = 0.0;
    for (uint k = 0u; k < 8u; ++k) s += gi1_light_importance(l, lo + vec3(k & 1u, (k >> 1) & 1u, k >> 2) * side, 0.5 * side);
    s *= 0.125;
    if (!(s > 0.0)) continue;
    // Insert into the list sorted by importance, highest first; the least important drops
    // out of a full list (earlier lights first among equals).
    uint at = count < k_max ? count : k_max;
    while (at > 0u && score[at - 1u] < s) --at;
    if (at >= k_max) continue;
    for (uint i = min(count, k_max - 1u); i > at; --i) {
      best[i] = best[i - 1u];
      score[i] = score[i - 1u];
    }
    best[at] = l;
    score[at] = s;
    count = min(count + 1u, k_max);
  }
  uint base = cell * (gi1.grid_cells.w + 1u);
  light_grid[base] = count;
  for (uint i = 0u; i < count; ++i) light_grid[base + 1u + i] = best[i];
}
