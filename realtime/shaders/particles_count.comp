#version 460
// The GPU particle system's bookkeeping between its passes (ParticleSystem::step), one
// invocation: the counts each pass reads and the indirect arguments of the next.
//   phase 0, before simulating: the last frame's alive list becomes this frame's input;
//   phase 1, before emitting: as many particles as requested, at most as many as are dead
//            (the simulation has just freed this frame's deaths);
//   phase 2, after emitting: the octahedra pass's arguments, eight invocations a particle
//            (particles_vertices.comp) in groups over two dimensions, each at most 65535
//            (Vulkan's least maxComputeWorkGroupCount).
#extension GL_GOOGLE_include_directive : require

#include "shaders/particles_bindings.glsl"

layout(local_size_x = 1) in;

layout(push_constant) uniform Push { uint phase; } pc;

uvec3 groups(uint n) { return uvec3((n + GIQ_PARTICLES_GROUP - 1u) / GIQ_PARTICLES_GROUP, 1u, 1u); }

void main() {
  if (pc.phase == 0u) {
    counters[GIQ_PARTICLES_IN] = counters[GIQ_PARTICLES_OUT];
    counters[GIQ_PARTICLES_OUT] = 0u;
    uvec3 g = groups(counters[GIQ_PARTICLES_IN]);
    indirect[GIQ_PARTICLES_SIMULATE_ARGS] = g.x, indirect[GIQ_PARTICLES_SIMULATE_ARGS + 1u] = g.y, indirect[GIQ_PARTICLES_SIMULATE_ARGS + 2u] = g.z;
  } else if (pc.phase == 1u) {
    uint n = min(frame.ids.y, counters[GIQ_PARTICLES_DEAD]);
    counters[GIQ_PARTICLES_EMIT] = n;
    uvec3 g = groups(n);
    indirect[GIQ_PARTICLES_EMIT_ARGS] = g.x, indirect[GIQ_PARTICLES_EMIT_ARGS + 1u] = g.y, indirect[GIQ_PARTICLES_EMIT_ARGS + 2u] = g.z;
  } else {
    uint n = groups(counters[GIQ_PARTICLES_OUT] * 8u).x, x = min(n, 65535u);
    uvec3 g = uvec3(x, x == 0u ? 0u : (n + x - 1u) / x, 1u);
    indirect[GIQ_PARTICLES_VERTICES_ARGS] = g.x, indirect[GIQ_PARTICLES_VERTICES_ARGS + 1u] = g.y, indirect[GIQ_PARTICLES_VERTICES_ARGS + 2u] = g.z;
  }
}
