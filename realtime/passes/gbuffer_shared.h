// Push constants of the G-buffer pass (gbuffer.cpp, gbuffer.vert, gbuffer.frag,
// gbuffer_rays.comp, motion_vectors.comp).
#ifndef GIQ_GBUFFER_SHARED_H
#define GIQ_GBUFFER_SHARED_H

#include "shaders/camera_shared.h"

#ifdef __cplusplus
namespace giq::realtime::gpu {
#endif

struct GBufferPush {
  GpuCamera camera;
  vec4 viewport;  // x width, y height, z near plane
};

// Motion vectors (motion_vectors.comp): the cameras of this frame and of the previous one.
struct MotionPush {
  GpuCamera current;
  GpuCamera previous;
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
