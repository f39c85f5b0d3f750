#version 460
// The GPU particle system's simulation (Turánszki 2017, "GPU-based particle simulation", step
// 4): each particle of the last frame's alive list either died since (its id is below the
// frame's first alive id: its slot goes back on the dead list) or is brought to this frame's
// instant, in closed form from its birth state, and appended to this frame's alive list.
#extension GL_GOOGLE_include_directive : require

#include "shaders/particles_bindings.glsl"
#include "shaders/particle_motion.glsl"

layout(local_size_x = GIQ_PARTICLES_GROUP) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= counters[GIQ_PARTICLES_IN]) return;
  uint slot = alive_in[i];
  uint id = particles[slot].info.x;
  if (id < frame.ids.z) {
    dead_list[atomicAdd(counters[GIQ_PARTICLES_DEAD], 1u)] = slot;
    return;
  }
  float age = particle_age(emitter, frame, id);
  vec3 p, v;
  particle_state(emitter, particles[slot].birth_position.xyz, particles[slot].birth_velocity.xyz, age, p, v);
  particles[slot].position = vec4(p, age);
  particles[slot].velocity = vec4(v, 0.0);
  particles[slot].info.y = particle_stage(frame, emitter.params.z, id);
  alive_out[atomicAdd(counters[GIQ_PARTICLES_OUT], 1u)] = slot;
}
