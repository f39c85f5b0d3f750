// Push constants of hybrid's sampling pass, shared by hybrid.cpp and hybrid_sample.comp.
#ifndef GIQ_HYBRID_SHARED_H
#define GIQ_HYBRID_SHARED_H

#include "shaders/camera_shared.h"

#ifdef __cplusplus
namespace giq::realtime::gpu {
using uint = uint32_t;
using uvec2 = glm::uvec2;
#endif

struct HybridSamplePush {
  GpuCamera camera;
  vec4 environment;     // constant environment radiance (rgb), w its map's texture or -1
  uvec2 size;           // the image's width and height
  uint max_bounces;     // surface interactions after the first hit (1: one bounce ray)
  uint light_count;     // punctual lights
  uint emissive_count;  // emissive triangles
  uint samples;         // samples per pixel in this frame, averaged
  uint first_sample;    // samples per pixel drawn in earlier frames: the random sequence's offset
  uint seed;
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
