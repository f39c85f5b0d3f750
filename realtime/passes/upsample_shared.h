// Structures shared by passes/upsample.cpp and upsample.comp.
#ifndef GIQ_UPSAMPLE_SHARED_H
#define GIQ_UPSAMPLE_SHARED_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace giq::realtime::gpu {
using uvec4 = glm::uvec4;
#endif

#define GIQ_UPSAMPLE_MODE_UPSAMPLE 0u
#define GIQ_UPSAMPLE_MODE_BLUR_X 1u
#define GIQ_UPSAMPLE_MODE_BLUR_Y 2u

struct UpsamplePush {
  uvec4 size;  // x, y full resolution; z factor k; w mode
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
