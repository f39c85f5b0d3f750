// Structures shared by techniques/ddgi/ddgi.cpp and the DDGI shaders.
#ifndef GIQ_DDGI_SHARED_H
#define GIQ_DDGI_SHARED_H

#include "shaders/camera_shared.h"

#ifdef __cplusplus
namespace giq::realtime::gpu {
using uvec2 = glm::uvec2;
using uvec4 = glm::uvec4;
using uint = uint32_t;
#endif

// Rays 0 .. GIQ_DDGI_FIXED_RAYS-1 of every probe keep the same directions each frame and serve
// relocation and classification only; the others are rotated each frame and blended
// (Majercik et al. 2021; RTXGI's documentation, "Fixed Probe Rays").
#define GIQ_DDGI_FIXED_RAYS 32u
// A probe's state (GpuDdgiProbe::offset.w).
#define GIQ_DDGI_ACTIVE 0.0
#define GIQ_DDGI_INACTIVE 1.0

// The probe volume: a grid of counts.x x counts.y x counts.z probes, `spacing` apart.
struct GpuDdgiVolume {
  vec4 origin;        // xyz the first probe's grid position; w probe spacing
  uvec4 counts;       // xyz probes per axis; w all probes
  uvec4 tiles;        // x probes per atlas row; y irradiance interior texels; z distance
                      // interior texels; w rays per probe
  vec4 atlas;         // xy 1 / irradiance atlas size; zw 1 / distance atlas size (texels)
  vec4 bias;          // x normal bias, y view bias (world units); z largest distance a
                      // probe stores; w irradiance gamma
  uvec4 switches;     // x Chebyshev visibility, y relocation, z classification
};

// Per probe: the relocation offset from its grid position and its state.
struct GpuDdgiProbe {
  vec4 offset;  // xyz world offset; w GIQ_DDGI_ACTIVE or GIQ_DDGI_INACTIVE
};

struct DdgiTracePush {  // ddgi_trace.comp
  vec4 rotation[3];   // rows of this frame's random rotation of the blended rays
  vec4 environment;   // rgb constant environment radiance, w its map's texture or -1 (shaders/environment.glsl)
  uint light_count;   // punctual lights
  uint area_light_count;
  uint feedback;      // 1: hits add the volume's irradiance (multi-bounce)
  float albedo_cap;   // the diffuse albedo at hits is capped here for the feedback
};

struct DdgiBlendPush {  // ddgi_blend.comp
  vec4 rotation[3];       // as DdgiTracePush::rotation
  float hysteresis;       // weight of the previous value
  float change_threshold; // relative change (encoded) that lowers the hysteresis
  float brightness_threshold;  // relative change (encoded) that is clamped
  uint pad;
};

struct DdgiProbePush {  // ddgi_probes.comp
  float backface_threshold;   // fraction of fixed rays hitting back faces: inside geometry
  float min_frontface;        // world distance a probe keeps from front faces
  float max_offset;           // largest offset per axis, world units
  uint pad;
};

struct DdgiShadePush {  // ddgi_shade.comp
  vec4 eye;    // the viewer: gpu_eye() (camera_shared.h)
  uvec2 size;  // the image's width and height
  uint pad0, pad1;
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
