#pragma once
// One emitter's particles simulated on the GPU as Turánszki 2017 ("GPU-based particle
// simulation") describes: a particle buffer of the emitter's capacity, a dead list of free
// slots, two alive lists that swap every frame, a counter buffer, and indirect arguments for
// the simulate and emit passes and for drawing the alive particles, written on the GPU from the
// counters. giq's particles are opaque scene geometry, so their draw is a compute pass that
// writes each alive particle's octahedron into the scene's vertex array (every pass then draws
// or traces the scene), dispatched by those arguments. Which particles are alive and what they
// do is scenes/particles.h's: the host makes the frame's integer decisions (the ids to emit,
// the first id alive, the stage starts) and the passes evaluate each particle in float, so the
// GPU holds the particles the scene library places for the reference, to float rounding
// (tests/realtime/particle_system_test.cpp).
//
// Two departures from the post: the simulation runs before the emission, so that this frame's
// deaths free their slots first and the capacity needed is the most particles alive at once
// (scenes::Emitter::max_particles); and the particles are not sorted, since giq renders them
// opaque (no blending needs an order).

#include <cstdint>
#include <vector>

#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"
#include "giq/scenes/particles.h"

namespace giq::realtime {

namespace gpu {
struct GpuParticleStage;  // shaders/particles_shared.h
}
class Context;
class GpuTimer;
class ShaderCompiler;

class ParticleSystem {
 public:
  ParticleSystem(Context& ctx, ShaderCompiler& compiler, const scenes::Emitter& emitter);

  // The host's part of bringing the particles to time t: this frame's ids and stage starts,
  // uploaded. A time before the last one's starts the system over (every slot dead).
  void prepare(double t);
  // The passes (bookkeeping, simulate, bookkeeping, emit, bookkeeping), each behind a barrier,
  // timed by `timer` when given as "particle simulation" (the first two) and "particle
  // emission" (the rest).
  void record(VkCommandBuffer cmd, GpuTimer* timer = nullptr);
  // The scene's arrays the particles are written into (SceneGpu's): gpu::GpuVertex rows now
  // and a frame earlier, gpu::GpuTriangle records, the index buffer and gpu::GpuEmissive.
  struct SceneArrays {
    const Buffer &vertices, &previous, &triangles, &indices, &emissive;
  };
  // After record(): writes this frame's alive particles as the scene library's octahedra into
  // `scene`, where each was `frame_seconds` earlier into its previous vertices
  // (shaders/particles_vertices.comp). Stage s's particles go where stages[s] says (its
  // lowest id filled in here), ids ascending, as scenes::Scene::at places them in its
  // stage's mesh.
  void record_vertices(VkCommandBuffer cmd, const SceneArrays& scene, const std::vector<gpu::GpuParticleStage>& stages,
                       double frame_seconds);
  // The particles of each stage of life at the prepared time.
  const std::vector<uint32_t>& stage_counts() const { return stage_count_; }

  struct Counts {
    uint32_t alive = 0, dead = 0, emitted = 0;
  };
  // After a step (blocking reads).
  Counts counts() const;
  struct State {
    uint32_t slot = 0, id = 0, stage = 0;
    glm::vec3 position{0.0f}, velocity{0.0f};
    float age = 0.0f;
  };
  std::vector<State> alive() const;  // in alive-list order
  std::vector<uint32_t> dead_slots() const;
  uint32_t capacity() const { return capacity_; }

 private:
  void reset();
  // The bindings every pass shares (shaders/particles_bindings.glsl), with alive lists `in` and
  // `out`.
  std::vector<Descriptor> descriptors(int in, int out) const;

  Context* ctx_;
  scenes::Emitter emitter_;  // a copy: posed scenes come and go
  uint32_t capacity_;
  Pipeline count_, simulate_, emit_, vertices_;
  Buffer particles_, dead_, alive_[2], counters_, indirect_, emitter_buffer_, frame_, surface_, choice_, stages_;
  uint64_t alive_count_ = 0;               // alive at the prepared time
  std::vector<uint32_t> stage_lowest_id_;  // the lowest id of each stage then (when it has any)
  std::vector<uint32_t> stage_count_;      // the particles in each stage then
  int out_ = 1;  // the alive list written this frame
  double last_t_ = -1.0;
  uint64_t emitted_end_ = 0;  // ids below were emitted (or skipped, dead before their frame)
};

}  // namespace giq::realtime
