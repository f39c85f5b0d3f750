#version 460
// The alive particles as the scene's geometry: each particle of this frame's alive list
// written as the scene library's octahedron (scenes/particle_geometry.cpp: six vertices on the
// axes at the emitter's size, normals along them) into the scene's vertex array, in its stage
// mesh at the place the scene library gives it (particle ids ascending within a stage), and
// where it was one frame earlier, by the same closed form at its age less a frame, into the
// previous vertices (motion vectors; before its birth too, as the scene library does). The
// vertices are the ones the GPU simulated, so every pass draws and traces this system's
// particles (SceneGpu refits the BVH over them).
#extension GL_GOOGLE_include_directive : require

#include "shaders/particles_bindings.glsl"
#include "shaders/particle_motion.glsl"
#include "shaders/particle_octahedron.glsl"

layout(local_size_x = GIQ_PARTICLES_GROUP) in;

layout(std430, binding = 10) writeonly buffer Vertices { vec4 vertices[]; };  // GpuVertex rows: position, normal
layout(std430, binding = 11) writeonly buffer Previous { vec4 previous[]; };
// Per stage of life: x its mesh's first vertex, y the lowest id in it.
layout(std430, binding = 12) readonly buffer Stages { uvec4 stages[]; };
layout(push_constant) uniform Push { float frame_seconds; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= counters[GIQ_PARTICLES_OUT]) return;
  uint slot = alive_out[i];
  vec4 position = particles[slot].position;  // w: age
  uint stage = floatBitsToUint(particles[slot].velocity.w);
  vec4 birth = particles[slot].birth_position;
  uint id = floatBitsToUint(birth.w);
  vec3 was, v;
  particle_state(birth.xyz, particles[slot].birth_velocity.xyz, position.w - frame_seconds, was, v);
  uint first = stages[stage].x + 6u * (id - stages[stage].y);
  float size = emitter.motion.w;
  for (uint k = 0u; k < 6u; ++k) {
    vec3 axis = kParticleAxes[k];
    uint row = 2u * (first + k);
    vertices[row] = vec4(position.xyz + size * axis, 1.0);
    vertices[row + 1u] = vec4(axis, 0.0);
    previous[row] = vec4(was + size * axis, 1.0);
    previous[row + 1u] = vec4(axis, 0.0);
  }
}
