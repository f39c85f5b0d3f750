#version 460
// Vertices pulled from the scene buffer by index; projected camera-relative (the camera's
// position is subtracted before anything else), with the pinhole of camera.glsl: clip x, y
// put a point on the pixel its camera ray goes through; depth = 1 - near / z.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "passes/gbuffer_shared.h"

layout(push_constant) uniform Push { GBufferPush pc; };

void main() {
  vec3 p = scene_vertices[gl_VertexIndex].position.xyz - pc.camera.position.xyz;
  float xv = dot(p, pc.camera.right.xyz), yv = dot(p, pc.camera.up.xyz), zv = dot(p, pc.camera.forward.xyz);
  float tan_half = pc.camera.forward.w, aspect = pc.size.x / pc.size.y;
  gl_Position = vec4(xv / (tan_half * aspect), -yv / tan_half, zv - pc.znear, zv);
}
