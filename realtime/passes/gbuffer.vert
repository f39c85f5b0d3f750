#version 460
// Vertices pulled from the scene buffer by index; projected camera-relative (the camera's
// position is subtracted before anything else), with the camera of camera.glsl: clip x, y
// put a point on the pixel its camera ray goes through. Depth: 1 - near / z for a pinhole,
// (z - near) * zscale for an orthographic camera (linear, as its clip w is 1).
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/camera.glsl"
#include "passes/gbuffer_shared.h"

layout(push_constant) uniform Push { GBufferPush pc; };

void main() {
  vec3 p = scene_vertices[gl_VertexIndex].position.xyz - pc.camera.position.xyz;
  float xv = dot(p, pc.camera.right.xyz), yv = dot(p, pc.camera.up.xyz), zv = dot(p, pc.camera.forward.xyz);
  float aspect = pc.size.x / pc.size.y;
  if (camera_orthographic(pc.camera)) {
    float half_h = pc.camera.right.w;
    gl_Position = vec4(xv / (half_h * aspect), -yv / half_h, (zv - pc.znear) * pc.zscale, 1.0);
  } else {
    float tan_half = pc.camera.forward.w;
    gl_Position = vec4(xv / (tan_half * aspect), -yv / tan_half, zv - pc.znear, zv);
  }
}
