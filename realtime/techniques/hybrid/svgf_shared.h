// Push constants and image contents of the SVGF passes (svgf.h), shared by svgf.cpp and the
// svgf_*.comp shaders.
//
// The filter's view of the surface at each pixel, written by the reprojection for this frame
// and kept for the next:
//   surface (RGBA32F): xy the shading normal, octahedral (shaders/octahedral.glsl); z the
//     linear depth along the camera's forward axis (0: no surface); w a bound on how much
//     the depth changes from one pixel to the next on this surface (the pixel footprint
//     times the sine of the angle between normal and forward axis), the scale of the depth
//     edge-stopping function in place of Schied et al.'s screen-space depth gradient
//   object (R32UI): the G-buffer's object id + 1 (0: no surface)
#ifndef GIQ_SVGF_SHARED_H
#define GIQ_SVGF_SHARED_H

#include "shaders/camera_shared.h"

#ifdef __cplusplus
namespace giq::realtime::gpu {
using uint = uint32_t;
using uvec2 = glm::uvec2;
#endif

struct SvgfReprojectPush {
  // Linear depth is measured from `eye` along `forward`: this frame's camera's for this
  // frame's surface, the previous frame's for comparing with the previous surface.
  vec4 eye;
  vec4 forward;
  vec4 previous_eye;
  vec4 previous_forward;
  uvec2 size;
  float alpha_colour;   // the colour's exponential moving average: weight of the new sample
  float alpha_moments;  // the same for the luminance moments
  float history_cap;    // the history length stops growing here (frames)
  uint history;         // 0: no history (first frame): every pixel starts again
  uint pad0, pad1;
};

struct SvgfFilterPush {
  uvec2 size;
  int step;           // the a-trous step 2^i (1 for the variance estimate)
  uint feedback;      // 1: also write the result as next frame's history
  float phi_colour;   // luminance edge-stopping, in standard deviations
  float phi_normal;   // exponent of the normal edge-stopping
  float pad0, pad1;
};

struct SvgfModulatePush {
  uvec2 size;
  uint pad0, pad1;
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
