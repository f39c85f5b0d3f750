// The bindings every pass of the GPU particle system shares (ParticleSystem).
#ifndef GIQ_PARTICLES_BINDINGS_GLSL
#define GIQ_PARTICLES_BINDINGS_GLSL

#include "shaders/particles_shared.h"

layout(std430, binding = 0) buffer Particles { GpuParticle particles[]; };
layout(std430, binding = 1) buffer Dead { uint dead_list[]; };
layout(std430, binding = 2) buffer AliveIn { uint alive_in[]; };    // the last frame's alive particles
layout(std430, binding = 3) buffer AliveOut { uint alive_out[]; };  // this frame's
layout(std430, binding = 4) buffer Counters { uint counters[]; };   // GIQ_PARTICLES_IN ...
layout(std430, binding = 5) buffer Indirect { uint indirect[]; };   // GIQ_PARTICLES_*_ARGS
layout(std430, binding = 6) readonly buffer Emitter { GpuEmitter emitter; };
layout(std430, binding = 7) readonly buffer Frame { GpuParticleFrame frame; };
layout(std430, binding = 8) readonly buffer Surface { vec4 surface[]; };  // three corners a triangle
layout(std430, binding = 9) readonly buffer Choice { uint choice[]; };

#endif
