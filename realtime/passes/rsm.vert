#version 460
// Reflective shadow map (Afanasev 2021, chapter II; Dachsbacher and Stamminger 2005): the scene
// rasterised from one light's view into one layer. Vertices pulled from the scene buffer.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "passes/rsm_shared.h"

layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 1) readonly buffer Layers { GpuRsmLayer layers[]; };

layout(push_constant) uniform Push { RsmLayerPush pc; };

layout(location = 0) out vec3 out_position;

void main() {
  vec3 p = scene_vertices[gl_VertexIndex].position.xyz;
  out_position = p;
  gl_Position = layers[pc.layer].view_proj * vec4(p, 1.0);
}
