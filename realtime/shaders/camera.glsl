// The camera of giq::scenes::Camera (scenes/src/camera.cpp), so a pixel of `giq realtime`
// looks through the same ray as a pixel of `giq reference`: pixel (i, j) covers
// [i, i+1) x [j, j+1), y down, aspect = width / height, and yfov (pinhole) or 2 ymag
// (orthographic) spans the height.
#ifndef GIQ_CAMERA_GLSL
#define GIQ_CAMERA_GLSL

#include "camera_shared.h"

bool camera_orthographic(GpuCamera cam) { return cam.right.w > 0.0; }

// Half the image's height: on the plane at distance 1 (pinhole), or on the plane through the
// camera (orthographic).
float camera_half_height(GpuCamera cam) { return camera_orthographic(cam) ? cam.right.w : cam.forward.w; }

// The pixel's point of that plane, relative to its centre.
vec3 camera_plane(GpuCamera cam, vec2 pixel, vec2 size) {
  float half_h = camera_half_height(cam), aspect = size.x / size.y;
  float x = (2.0 * pixel.x / size.x - 1.0) * half_h * aspect;
  float y = (1.0 - 2.0 * pixel.y / size.y) * half_h;
  return x * cam.right.xyz + y * cam.up.xyz;
}

vec3 camera_ray_direction(GpuCamera cam, vec2 pixel, vec2 size) {
  return camera_orthographic(cam) ? cam.forward.xyz : normalize(cam.forward.xyz + camera_plane(cam, pixel, size));
}

vec3 camera_ray_origin(GpuCamera cam, vec2 pixel, vec2 size) {
  return cam.position.xyz + (camera_orthographic(cam) ? camera_plane(cam, pixel, size) : vec3(0.0));
}

// How far apart on the surface the rays of neighbouring pixels land: the larger of the
// distances from p (on the plane through p with normal n) to where the rays through
// pixel + (1, 0) and pixel + (0, 1) meet that plane (ray differentials by finite differences,
// Igehy 1999; a pixel's footprint side as GPUs take it for mip selection: the longer of the
// two screen-axis derivatives). 1e30 where a neighbour's ray runs parallel to the plane.
float pixel_footprint(GpuCamera cam, vec2 pixel, vec2 size, vec3 p, vec3 n) {
  float f = 0.0;
  for (int axis = 0; axis < 2; ++axis) {
    vec2 q = pixel + (axis == 0 ? vec2(1.0, 0.0) : vec2(0.0, 1.0));
    vec3 o = camera_ray_origin(cam, q, size), d = camera_ray_direction(cam, q, size);
    float den = dot(d, n);
    if (abs(den) < 1e-12) return 1e30;
    f = max(f, length(o + (dot(p - o, n) / den) * d - p));
  }
  return min(f, 1e30);
}

// The inverse: the image point (in pixels, as camera_ray_direction takes it) where the point
// p appears, and its distance along forward; z > 0 when p is in front of the camera.
vec3 camera_project(GpuCamera cam, vec3 p, vec2 size) {
  vec3 d = p - cam.position.xyz;
  float z = dot(d, cam.forward.xyz);
  float half_h = camera_orthographic(cam) ? cam.right.w : z * cam.forward.w, aspect = size.x / size.y;
  float x = dot(d, cam.right.xyz) / (half_h * aspect);
  float y = dot(d, cam.up.xyz) / half_h;
  return vec3(0.5 * (x + 1.0) * size.x, 0.5 * (1.0 - y) * size.y, z);
}

// Unit vector from p towards the viewer.
vec3 camera_to_eye(GpuCamera cam, vec3 p) {
  return camera_orthographic(cam) ? -cam.forward.xyz : normalize(cam.position.xyz - p);
}
// The same from gpu_eye() (camera_shared.h), for passes that push only that.
vec3 camera_to_eye(vec4 eye, vec3 p) { return eye.w > 0.0 ? normalize(eye.xyz - p) : eye.xyz; }

#endif
