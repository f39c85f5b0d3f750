#version 460
// Depth-only rendering of the scene into one shadow-map layer.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"

layout(push_constant) uniform Push { mat4 view_proj; } pc;

void main() { gl_Position = pc.view_proj * vec4(scene_vertices[gl_VertexIndex].position.xyz, 1.0); }
