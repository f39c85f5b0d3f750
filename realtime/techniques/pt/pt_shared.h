// Push constants of the GPU path tracer, shared by pt.cpp and pt.comp.
#ifndef GIQ_PT_SHARED_H
#define GIQ_PT_SHARED_H

#include "shaders/camera_shared.h"

#ifdef __cplusplus
namespace giq::realtime::gpu {
using uint = uint32_t;
#endif

struct PtPush {
  GpuCamera camera;
  vec4 environment;        // constant environment radiance (rgb), w its map's texture or -1 (shaders/environment.glsl)
  uint width;
  uint height;
  uint first_sample;       // samples accumulated before this dispatch
  uint samples_per_frame;  // paths per pixel in this dispatch (pt.cpp sends 1)
  uint max_bounces;        // path vertices after the camera
  uint emissive_count;
  uint light_count;
  uint seed;
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
