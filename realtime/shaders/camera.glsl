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

#endif
