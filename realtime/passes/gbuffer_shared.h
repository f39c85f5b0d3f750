// Push constants of the G-buffer pass (gbuffer.cpp, gbuffer.vert, gbuffer.frag).
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

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
