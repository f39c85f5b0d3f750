#version 460
// The GPU particle system's simulation (Turánszki 2017, "GPU-based particle simulation", step
// 4): each particle of the last frame's alive list either died since (its id is below the
// frame's first alive id: its slot goes back on the dead list) or is brought to this frame's
// instant, in closed form from its birth state, and appended to this frame's alive list.
#extension GL_GOOGLE_include_directive : require

#include "shaders/particles_bindings.glsl"
#include "shaders/particle_lists.glsl"
#include "shaders/particle_motion.glsl"

layout(local_size_x = GIQ_PARTICLES_GROUP) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  bool present = i < counters[GIQ_PARTICLES_IN];
  uint slot = present ? alive_in[i] : 0u;
  vec4 birth = present ? particles[slot].birth_position : vec4(0.0);
  uint id = floatBitsToUint(birth.w);
  bool dies = present && id < frame.ids.z;
  bool lives = present && !dies;
  uint dead_at = subgroup_atomic_add(GIQ_PARTICLES_DEAD, dies, 1u);
  uint alive_at = subgroup_atomic_add(GIQ_PARTICLES_OUT, lives, 1u);
  if (dies) dead_list[dead_at] = slot;
  if (!lives) return;
  float age = particle_age(id);
  vec3 p, v;
  particle_state(birth.xyz, particles[slot].birth_velocity.xyz, age, p, v);
  particles[slot].position = vec4(p, age);
  particles[slot].velocity = vec4(v, uintBitsToFloat(particle_stage(id)));
  alive_out[alive_at] = slot;
}
