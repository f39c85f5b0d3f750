// Push constants of the G-buffer pass (gbuffer.cpp, gbuffer.vert, gbuffer.frag,
// gbuffer_rays.comp, motion_vectors.comp).
#ifndef GIQ_GBUFFER_SHARED_H
#define GIQ_GBUFFER_SHARED_H

#include "shaders/camera_shared.h"

#ifdef __cplusplus
namespace giq::realtime::gpu {
using vec2 = glm::vec2;
#endif

struct GBufferPush {
  GpuCamera camera;
  vec2 size;    // the image's width and height
  float znear;  // the rasteriser's near plane; the ray caster's minimum distance along forward
  float zscale; // orthographic: 1 / (farthest scene depth - znear), so depth spans [0, 1]
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
