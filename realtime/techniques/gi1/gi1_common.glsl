// What every `gi1` pass that reads the G-buffer binds after it (passes/receiver.glsl): the
// frame's constants, both frames' probes, radiance maps and spherical harmonics. Which of the
// two is this frame's alternates (gi1.cpp binds them swapped on odd frames). A pass that
// defines GIQ_GI1_FRAME_ONLY first binds the frame's constants alone (push descriptors are
// limited to 32).
#ifndef GIQ_GI1_COMMON_GLSL
#define GIQ_GI1_COMMON_GLSL

layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 0) readonly buffer Frame { GpuGi1Frame gi1; };
#ifdef GIQ_GI1_FRAME_ONLY
#define GIQ_GI1_BINDING_COUNT (GIQ_RECEIVER_BINDING_COUNT + 1)
#else
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 1) buffer Probes { GpuGi1Probe probes[]; };
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 2) readonly buffer PreviousProbes {
  GpuGi1Probe previous_probes[];
};
// A probe's 64 cells: rgb radiance, w the distance its ray travelled.
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 3) buffer Radiance { vec4 radiance[]; };
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 4) readonly buffer PreviousRadiance { vec4 previous_radiance[]; };
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 5) buffer Harmonics { vec4 harmonics[]; };
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 6) readonly buffer PreviousHarmonics {
  vec4 previous_harmonics[];
};
#define GIQ_GI1_BINDING_COUNT (GIQ_RECEIVER_BINDING_COUNT + 7)
#endif

uint gi1_tile_index(uvec2 tile) { return tile.x + tile.y * gi1.size.z; }

#endif
