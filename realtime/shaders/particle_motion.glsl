// A particle's emission and motion (scenes/particles.h, evaluated there in double precision for
// the reference) in float: the same random words, the same integer choice of triangle, the same
// closed form. Where the CPU calls std::sin, std::cos and std::expm1, the GPU uses polynomials
// accurate to a few float ulps, since Vulkan only bounds sin and cos to 2^-11 absolutely. The
// emitter and the frame are read from their buffers where needed, not passed by value: a copy
// of the frame's 288 bytes per invocation would cost more than the particle itself.
#ifndef GIQ_PARTICLE_MOTION_GLSL
#define GIQ_PARTICLE_MOTION_GLSL

#include "shaders/particles_bindings.glsl"
#include "shaders/sampling.glsl"

uint particle_random(uint seed, uint id, uint k) { return pcg_hash(k ^ pcg_hash(id ^ pcg_hash(seed))); }
float particle_unit(uint seed, uint id, uint k) { return float(particle_random(seed, id, k) >> 8u) * (1.0 / 16777216.0); }

// sin and cos of 2 pi u: reduced exactly to a quarter turn f in [-1/2, 1/2], then Taylor
// polynomials on [-pi/4, pi/4] (truncation below 2e-9).
vec2 sincos_turns(float u) {
  float x4 = 4.0 * (u - round(u));  // exact: u has 24 bits
  float q = round(x4);
  float y = (x4 - q) * (0.5 * PI), y2 = y * y;
  float s = y * (1.0 + y2 * (-1.0 / 6.0 + y2 * (1.0 / 120.0 + y2 * (-1.0 / 5040.0 + y2 * (1.0 / 362880.0)))));
  float c = 1.0 + y2 * (-0.5 + y2 * (1.0 / 24.0 + y2 * (-1.0 / 720.0 + y2 * (1.0 / 40320.0 + y2 * (-1.0 / 3628800.0)))));
  int quadrant = int(q) & 3;
  return quadrant == 0 ? vec2(s, c) : quadrant == 1 ? vec2(c, -s) : quadrant == 2 ? vec2(-s, -c) : vec2(-c, s);
}

// phi1(z) = (e^z - 1) / z = sum z^k / (k + 1)! and phi2(z) = (e^z - 1 - z) / z^2 =
// sum z^k / (k + 2)!: ten terms for |z| < 1 (truncation below 3e-8), where the closed forms
// would cancel; exp beyond.
const float kInverseFactorial[12] = float[12](1.0, 1.0, 1.0 / 2.0, 1.0 / 6.0, 1.0 / 24.0, 1.0 / 120.0, 1.0 / 720.0, 1.0 / 5040.0,
                                              1.0 / 40320.0, 1.0 / 362880.0, 1.0 / 3628800.0, 1.0 / 39916800.0);
float phi1(float z) {
  if (abs(z) >= 1.0) return (exp(z) - 1.0) / z;
  float r = kInverseFactorial[10];
  for (int k = 8; k >= 0; --k) r = r * z + kInverseFactorial[k + 1];
  return r;
}
float phi2(float z) {
  if (abs(z) >= 1.0) return (exp(z) - 1.0 - z) / (z * z);
  float r = kInverseFactorial[11];
  for (int k = 8; k >= 0; --k) r = r * z + kInverseFactorial[k + 2];
  return r;
}

// The particle at `age` from its birth state, in closed form (scenes/particles.h).
void particle_state(vec3 p0, vec3 v0, float age, out vec3 p, out vec3 v) {
  vec4 g = emitter.gravity;
  float z = -g.w * age, f1 = age * phi1(z);
  v = v0 * exp(z) + g.xyz * f1;
  p = p0 + v0 * f1 + g.xyz * (age * age * phi2(z));
}

// The stage of life of an alive particle: how many of the frame's stage starts lie above its id.
uint particle_stage(uint id) {
  uint stage = 0u;
  for (uint s = 0u; s + 1u < emitter.params.z; ++s) stage += id < frame.starts[s >> 2u][s & 3u] ? 1u : 0u;
  return stage;
}

// Its age at this frame: the anchor's, less its birth after the anchor's (a small integer
// times 1 / rate, so no large times meet in float).
float particle_age(uint id) { return frame.time.x - float(id - frame.ids.w) * emitter.motion.z; }

#endif
