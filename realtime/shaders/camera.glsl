// The pinhole camera of giq::scenes::Camera::ray_direction (scenes/src/camera.cpp), so a pixel
// of `giq realtime` looks through the same ray as a pixel of `giq reference`: pixel (i, j)
// covers [i, i+1) x [j, j+1), y down, aspect = width / height, yfov spans the height.
#ifndef GIQ_CAMERA_GLSL
#define GIQ_CAMERA_GLSL

#include "camera_shared.h"

vec3 camera_ray_direction(GpuCamera cam, vec2 pixel, vec2 size) {
  float tan_half = cam.forward.w, aspect = size.x / size.y;
  float x = (2.0 * pixel.x / size.x - 1.0) * tan_half * aspect;
  float y = (1.0 - 2.0 * pixel.y / size.y) * tan_half;
  return normalize(cam.forward.xyz + x * cam.right.xyz + y * cam.up.xyz);
}

// The inverse: the image point (in pixels, as camera_ray_direction takes it) where the point
// p appears; w > 0 when p is in front of the camera.
vec3 camera_project(GpuCamera cam, vec3 p, vec2 size) {
  vec3 d = p - cam.position.xyz;
  float z = dot(d, cam.forward.xyz);
  float tan_half = cam.forward.w, aspect = size.x / size.y;
  float x = dot(d, cam.right.xyz) / (z * tan_half * aspect);
  float y = dot(d, cam.up.xyz) / (z * tan_half);
  return vec3(0.5 * (x + 1.0) * size.x, 0.5 * (1.0 - y) * size.y, z);
}

// Where a direction (a point at infinity, e.g. the environment) appears.
vec3 camera_project_direction(GpuCamera cam, vec3 d, vec2 size) {
  return camera_project(cam, cam.position.xyz + d, size);
}

#endif
