#version 460
// Depth-only rendering of the scene into one shadow-map layer.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"

#include "passes/shadow_maps_shared.h"

layout(push_constant) uniform Push { ShadowPush pc; };

#ifdef GIQ_ALPHA_MASK
// Texture coordinates and COLOR_0's alpha for the cut-out test of shadow_maps.frag;
// perspective-correct interpolation gives the surface point's own values.
layout(location = 0) out vec4 out_uv;  // both mappings (GpuVertexExtra::uv)
layout(location = 1) out float out_alpha;
#endif

void main() {
  gl_Position = pc.view_proj * vec4(scene_vertices[gl_VertexIndex].position.xyz, 1.0);
  // A left-out vertex goes beyond the right clip plane, and so does its whole triangle (a
  // mesh's triangles use only its own vertices).
  if (uint(gl_VertexIndex) - pc.skip.x < pc.skip.y) gl_Position = vec4(2.0, 0.0, 0.5, 1.0);
#ifdef GIQ_ALPHA_MASK
  out_uv = scene_vertex_extra[gl_VertexIndex].uv;
  out_alpha = scene_vertex_extra[gl_VertexIndex].color.a;
#endif
}
