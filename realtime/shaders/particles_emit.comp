#version 460
// The GPU particle system's emission (Turánszki 2017, "GPU-based particle simulation", step
// 3), after the simulation here so that the slots freed by this frame's deaths are reused and
// the capacity is the most particles alive at once: each new particle takes a slot from the
// dead list, is emitted as scenes/particles.h says (a point on the surface chosen by area, a
// direction in the cone about its normal), brought to this frame's instant (it was born
// between the frames) and appended to this frame's alive list.
#extension GL_GOOGLE_include_directive : require

#include "shaders/particles_bindings.glsl"
#include "shaders/particle_lists.glsl"
#include "shaders/particle_motion.glsl"

layout(local_size_x = GIQ_PARTICLES_GROUP) in;

// Where and how particle `id` is emitted: on the triangle its word 0 chooses (the first k with
// choice[k] >= the word, compared as integers, as on the CPU), uniform over it (words 1, 2),
// at the emitter's speed in a direction uniform over the cone about the face's normal (words 3,
// 4), in a tangent frame by Duff et al. 2017 ("Building an Orthonormal Basis, Revisited").
void emission(uint id, out vec3 p0, out vec3 v0) {
  uint seed = emitter.params.y, r = particle_random(seed, id, 0u);
  uint lo = 0u, hi = emitter.params.x - 1u;
  while (lo < hi) {
    uint mid = (lo + hi) >> 1u;
    if (choice[mid] < r) lo = mid + 1u;
    else hi = mid;
  }
  vec3 a = surface[3u * lo].xyz, b = surface[3u * lo + 1u].xyz, c = surface[3u * lo + 2u].xyz;
  float s = sqrt(particle_unit(seed, id, 1u)), u = particle_unit(seed, id, 2u);
  p0 = a + s * ((b - a) + u * (c - b));
  vec3 n = normalize(cross(b - a, c - a));
  float sgn = n.z >= 0.0 ? 1.0 : -1.0, ka = -1.0 / (sgn + n.z), kb = n.x * n.y * ka;
  vec3 tx = vec3(1.0 + sgn * n.x * n.x * ka, sgn * kb, -sgn * n.x), ty = vec3(kb, sgn + n.y * n.y * ka, -n.y);
  // sin from 1 - cos (x (2 - x) = 1 - cos^2), which does not cancel near the cone's axis.
  float x = particle_unit(seed, id, 3u) * emitter.motion.y, cos_theta = 1.0 - x, sin_theta = sqrt(x * (2.0 - x));
  vec2 phi = sincos_turns(particle_unit(seed, id, 4u));
  v0 = emitter.motion.x * (cos_theta * n + sin_theta * (phi.y * tx + phi.x * ty));
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  bool emits = i < counters[GIQ_PARTICLES_EMIT];
  // Popped from the dead list's end: the counter less one, less this invocation's rank.
  uint dead_at = subgroup_atomic_add(GIQ_PARTICLES_DEAD, emits, 0xffffffffu);
  uint alive_at = subgroup_atomic_add(GIQ_PARTICLES_OUT, emits, 1u);
  if (!emits) return;
  uint slot = dead_list[dead_at - 1u];
  uint id = frame.ids.x + i;
  vec3 p0, v0, p, v;
  emission(id, p0, v0);
  float age = particle_age(id);
  particle_state(p0, v0, age, p, v);
  particles[slot].birth_position = vec4(p0, uintBitsToFloat(id));
  particles[slot].birth_velocity = vec4(v0, 0.0);
  particles[slot].position = vec4(p, age);
  particles[slot].velocity = vec4(v, uintBitsToFloat(particle_stage(id)));
  alive_out[alive_at] = slot;
}
