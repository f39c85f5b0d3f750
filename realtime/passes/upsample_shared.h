// Structures shared by passes/upsample.cpp and upsample.comp.
#ifndef GIQ_UPSAMPLE_SHARED_H
#define GIQ_UPSAMPLE_SHARED_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace giq::realtime::gpu {
using uvec2 = glm::uvec2;
using uint = uint32_t;
#endif

#define GIQ_UPSAMPLE_MODE_UPSAMPLE 0u
#define GIQ_UPSAMPLE_MODE_BLUR_X 1u
#define GIQ_UPSAMPLE_MODE_BLUR_Y 2u

struct UpsamplePush {
  uvec2 size;   // full resolution
  uint factor;  // k: the low-resolution image is 1/k of it per axis
  uint mode;    // GIQ_UPSAMPLE_MODE_*
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
