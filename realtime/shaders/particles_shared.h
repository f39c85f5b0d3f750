// The GPU particle system's buffers (ParticleSystem, shaders/particles_*.comp): one layout for
// the C++ that fills them and the GLSL that reads them (std430, 16-byte rows).
#ifndef GIQ_PARTICLES_SHARED_H
#define GIQ_PARTICLES_SHARED_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace giq::realtime::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using uint = uint32_t;
#endif

// The counter buffer's words.
#define GIQ_PARTICLES_IN 0u    // alive at the last frame: the list simulated now
#define GIQ_PARTICLES_DEAD 1u  // free slots on the dead list
#define GIQ_PARTICLES_EMIT 2u  // emitted this frame: min(requested, dead)
#define GIQ_PARTICLES_OUT 3u   // alive now: the list the next frame simulates
// The indirect argument buffer's words: VkDispatchIndirectCommand for simulate, emit and the
// pass that draws the alive particles into the scene as octahedra (particles_vertices.comp:
// giq's particles are scene geometry, which every pass then draws or traces).
#define GIQ_PARTICLES_SIMULATE_ARGS 0u
#define GIQ_PARTICLES_EMIT_ARGS 3u
#define GIQ_PARTICLES_VERTICES_ARGS 6u
#define GIQ_PARTICLES_GROUP 256u  // invocations per group of every particle pass

// One particle, 64 bytes: its state at the last frame (what renderers read, written by the
// simulation) in the first 32-byte half, where and how it was emitted (read by the simulation)
// in the second, so that simulating one touches two aligned 32-byte sectors.
struct GpuParticle {
  vec4 position;        // xyz; w age (s)
  vec4 velocity;        // xyz; w the stage of life (uint bits)
  vec4 birth_position;  // xyz; w the id (uint bits)
  vec4 birth_velocity;  // xyz
};

// The emitter (scenes::Emitter) as every pass reads it.
struct GpuEmitter {
  vec4 gravity;  // xyz; w drag (1/s)
  vec4 motion;   // x speed, y 1 - cos(spread), z 1 / rate, w size
  uvec4 params;  // x surface triangles, y seed, z stages, w capacity
};

// This frame (ParticleSystem::step), from the host's integer decisions (scenes::alive_range,
// scenes::stage_starts).
struct GpuParticleFrame {
  uvec4 ids;     // x first id to emit, y ids to emit, z first id alive, w anchor id
  vec4 time;     // x the anchor's age (t - anchor / rate, in double on the host)
  uvec4 starts[16];  // stage_starts, four a row (63 at most)
};

// A stage of life of an emitter's particles as the scene holds it (SceneGpu), for the pass
// that writes them into the scene (particles_vertices.comp): particle k of the stage (its ids
// ascending) has vertices first.x + 6k.., triangles first.z + 8k.. and, when the stage glows,
// emissive triangles first.w - 1 + 8k.., their CDF values sampling.x + (j + 1) sampling.y for
// the stage's j-th one (all of a stage's triangles have one power, so the prefix sum has a
// closed form).
struct GpuParticleStage {
  uvec4 first;     // x first vertex, y the stage's lowest id, z first triangle, w first emissive triangle + 1 (0: dark)
  uvec4 triangle;  // x material, y object id, z GIQ_TRIANGLE_HAS_* bits, w emissive triangles in the scene (the last has CDF 1)
  vec4 radiance;   // rgb emitted radiance; w a face's area
  vec4 sampling;   // x the CDF before the stage's first triangle, y each triangle's probability
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
