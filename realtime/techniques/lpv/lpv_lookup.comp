#version 460
// LPV lookup at shading time (Afanasev 2021, chapter III; Kaplanyan and Dachsbacher 2010, section
// 5): the accumulated volume sampled trilinearly at the G-buffer point moved half a cell along
// its normal (less self-illumination and bleeding through thin geometry), its intensity turned
// into radiance by the cell's face area (L = I / cell^2), integrated against the cosine lobe
// of the surface: E = max(0, sh . cos_lobe_sh(-n)) / cell^2 per channel; out = albedo / pi x E
// x intensity.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/surface.glsl"
#include "passes/rsm_albedo.glsl"
#include "techniques/lpv/lpv_shared.h"
#include "techniques/lpv/lpv_sh.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

#include "passes/receiver.glsl"
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 0) readonly buffer Accumulated { vec4 accumulated[]; };
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 1, rgba32f) uniform writeonly image2D out_indirect;

layout(push_constant) uniform Push { LpvLookupPush pc; };

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  LpvGrid grid = pc.grid;
  if (any(greaterThanEqual(uvec2(px), pc.size))) return;
  Receiver r = load_receiver(px);
  vec3 radiance = vec3(0.0);
  if (r.lit) {
    vec3 x = r.x, n = r.n;
    float cell = grid.origin.w;
    int res = int(grid.resolution);
    // Cell centres at integer coordinates of g.
    vec3 g = (x - grid.origin.xyz) / cell + 0.5 * n - 0.5;
    ivec3 g0 = ivec3(floor(g));
    vec3 t = g - vec3(g0);
    vec4 sr = vec4(0.0), sg = vec4(0.0), sb = vec4(0.0);
    for (int i = 0; i < 8; ++i) {
      ivec3 o = ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
      ivec3 c = clamp(g0 + o, ivec3(0), ivec3(res - 1));
      vec3 w3 = mix(1.0 - t, t, vec3(o));
      float w = w3.x * w3.y * w3.z;
      int k = 3 * lpv_cell_index(c, res);
      sr += w * accumulated[k];
      sg += w * accumulated[k + 1];
      sb += w * accumulated[k + 2];
    }
    // Outside the grid: no indirect light.
    bool inside = all(greaterThanEqual(g, vec3(-0.5))) && all(lessThan(g, vec3(float(res) - 0.5)));
    vec4 lobe = cos_lobe_sh(-n);
    vec3 e = inside ? max(vec3(dot(sr, lobe), dot(sg, lobe), dot(sb, lobe)), vec3(0.0)) / (cell * cell) : vec3(0.0);
    radiance = diffuse_albedo(receiver_surface(r)) / PI * e * grid.intensity;
  }
  imageStore(out_indirect, px, vec4(radiance, 1.0));
}
