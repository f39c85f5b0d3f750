// The camera as shaders receive it (push constants), filled by camera_gpu() in C++.
#ifndef GIQ_CAMERA_SHARED_H
#define GIQ_CAMERA_SHARED_H

#ifdef __cplusplus
#include <cmath>
#include <glm/glm.hpp>

#include "giq/scenes/camera.h"
namespace giq::realtime::gpu {
using vec4 = glm::vec4;
#endif

struct GpuCamera {
  vec4 position;  // xyz local frame
  vec4 forward;   // xyz unit; w: tan(yfov / 2)
  vec4 right;     // xyz unit; w: Camera::ymag (> 0: orthographic)
  vec4 up;        // xyz unit
};

#ifdef __cplusplus
inline GpuCamera make_gpu_camera(const scenes::Camera& c) {
  return {glm::vec4(c.position, 1.0f), glm::vec4(c.forward, std::tan(0.5f * c.yfov)), glm::vec4(c.right, c.ymag),
          glm::vec4(c.up, 0.0f)};
}

// The viewer for passes that need only the direction to it (camera_to_eye in camera.glsl):
// the camera's position with w = 1, or for an orthographic camera -forward with w = 0.
inline glm::vec4 gpu_eye(const scenes::Camera& c) {
  return c.orthographic() ? glm::vec4(-c.forward, 0.0f) : glm::vec4(c.position, 1.0f);
}
}  // namespace giq::realtime::gpu
#endif
#endif
