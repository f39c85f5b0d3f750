#include "giq/realtime/particle_system.h"

#include <algorithm>
#include <cstring>
#include <numeric>

#include "giq/realtime/context.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"
#include "shaders/particles_shared.h"

namespace giq::realtime {

namespace {
constexpr uint32_t kBindings = 10;
}

ParticleSystem::ParticleSystem(Context& ctx, ShaderCompiler& compiler, const scenes::Emitter& emitter)
    : ctx_(&ctx), emitter_(emitter), capacity_(std::max<uint32_t>(1, emitter.max_particles)) {
  using namespace gpu;
  const std::vector<VkDescriptorType> bindings(kBindings, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  count_ = Pipeline::compute(ctx, compiler.compile("shaders/particles_count.comp"), bindings, sizeof(uint32_t));
  simulate_ = Pipeline::compute(ctx, compiler.compile("shaders/particles_simulate.comp"), bindings, 0);
  emit_ = Pipeline::compute(ctx, compiler.compile("shaders/particles_emit.comp"), bindings, 0);
  std::vector<VkDescriptorType> vertex_bindings = bindings;
  vertex_bindings.resize(kBindings + 6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  vertices_ = Pipeline::compute(ctx, compiler.compile("shaders/particles_vertices.comp"), vertex_bindings, sizeof(float));
  stages_ = Buffer(ctx, uint64_t(std::max(1, emitter.stages)) * sizeof(GpuParticleStage), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);

  particles_ = Buffer(ctx, uint64_t(capacity_) * sizeof(GpuParticle), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  dead_ = Buffer(ctx, uint64_t(capacity_) * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  for (Buffer& a : alive_) a = Buffer(ctx, uint64_t(capacity_) * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  counters_ = Buffer(ctx, 4 * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  indirect_ = Buffer(ctx, 16 * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
  frame_ = Buffer(ctx, sizeof(GpuParticleFrame), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);

  GpuEmitter e;
  e.gravity = glm::vec4(glm::vec3(emitter.gravity), float(emitter.drag));
  e.motion = glm::vec4(float(emitter.speed), float(1.0 - std::cos(emitter.spread)), float(1.0 / emitter.rate), float(emitter.size));
  e.params = glm::uvec4(uint32_t(emitter.choice.size()), emitter.seed, uint32_t(emitter.stages), capacity_);
  emitter_buffer_ = Buffer::storage(ctx, &e, sizeof(e));
  std::vector<glm::vec4> corners;
  for (const glm::dvec3& c : emitter.surface) corners.emplace_back(glm::vec3(c), 0.0f);
  surface_ = Buffer::storage(ctx, corners);
  choice_ = Buffer::storage(ctx, emitter.choice);
  reset();
}

void ParticleSystem::reset() {
  // Every slot dead, popped from the end of the list: slot 0 first.
  std::vector<uint32_t> dead(capacity_);
  std::iota(dead.rbegin(), dead.rend(), 0u);
  dead_.upload(dead.data(), dead.size() * sizeof(uint32_t));
  const uint32_t counters[4] = {0u, capacity_, 0u, 0u};
  counters_.upload(counters, sizeof(counters));
  emitted_end_ = 0;
  out_ = 1;
}

void ParticleSystem::prepare(double t) {
  if (t < last_t_) reset();
  last_t_ = t;
  const scenes::Emitter& e = emitter_;
  const scenes::AliveRange alive = scenes::alive_range(e, t);
  gpu::GpuParticleFrame f{};
  // The ids born since the last frame and still alive; those born and dead in between are
  // never emitted.
  const uint64_t first_new = std::max(emitted_end_, alive.first);
  f.ids = glm::uvec4(uint32_t(first_new), uint32_t(alive.end > first_new ? alive.end - first_new : 0), uint32_t(alive.first), uint32_t(alive.first));
  f.time = glm::vec4(float(t - double(alive.first) / e.rate), 0.0f, 0.0f, 0.0f);
  const std::vector<uint64_t> starts = scenes::stage_starts(e, t);
  for (size_t s = 0; s < starts.size(); ++s) f.starts[s / 4][int(s % 4)] = uint32_t(std::min<uint64_t>(starts[s], 0xffffffffu));
  emitted_end_ = std::max(emitted_end_, alive.end);
  frame_.upload(&f, sizeof(f));
  alive_count_ = alive.count();
  stage_lowest_id_.clear();
  stage_count_.clear();
  for (int s = 0; s < e.stages; ++s) {
    const scenes::AliveRange r = scenes::stage_range(alive, starts, s);
    stage_lowest_id_.push_back(uint32_t(r.first));
    stage_count_.push_back(uint32_t(r.count()));
  }
}

std::vector<Descriptor> ParticleSystem::descriptors(int in, int out) const {
  return {Descriptor::storage(particles_),      Descriptor::storage(dead_),  Descriptor::storage(alive_[in]),
          Descriptor::storage(alive_[out]),     Descriptor::storage(counters_), Descriptor::storage(indirect_),
          Descriptor::storage(emitter_buffer_), Descriptor::storage(frame_), Descriptor::storage(surface_),
          Descriptor::storage(choice_)};
}

void ParticleSystem::record(VkCommandBuffer cmd, GpuTimer* timer) {
  const int in = 1 - out_;
  const std::vector<Descriptor> d = descriptors(in, out_);
  auto count = [&](uint32_t phase) {
    count_.bind(cmd);
    count_.push_descriptors(cmd, d);
    count_.push_constants(cmd, phase);
    vkCmdDispatch(cmd, 1, 1, 1);
    full_barrier(cmd);
  };
  if (timer) timer->begin(cmd, "particle simulation");
  count(0);
  simulate_.bind(cmd);
  simulate_.push_descriptors(cmd, d);
  vkCmdDispatchIndirect(cmd, indirect_.handle(), GIQ_PARTICLES_SIMULATE_ARGS * sizeof(uint32_t));
  full_barrier(cmd);
  if (timer) timer->end(cmd), timer->begin(cmd, "particle emission");
  count(1);
  emit_.bind(cmd);
  emit_.push_descriptors(cmd, d);
  vkCmdDispatchIndirect(cmd, indirect_.handle(), GIQ_PARTICLES_EMIT_ARGS * sizeof(uint32_t));
  full_barrier(cmd);
  count(2);
  if (timer) timer->end(cmd);
  out_ = in;  // this frame's output is the next frame's input
}

void ParticleSystem::record_vertices(VkCommandBuffer cmd, const SceneArrays& scene, const std::vector<gpu::GpuParticleStage>& places,
                                     double frame_seconds) {
  if (alive_count_ == 0) return;
  std::vector<gpu::GpuParticleStage> stages = places;
  stages.resize(stage_lowest_id_.size());
  for (size_t s = 0; s < stages.size(); ++s) stages[s].first.y = stage_lowest_id_[s];
  stages_.upload(stages.data(), stages.size() * sizeof(gpu::GpuParticleStage));
  // record() made the list it wrote (alive_out here) the next frame's input.
  std::vector<Descriptor> d = descriptors(out_, 1 - out_);
  d.insert(d.end(), {Descriptor::storage(scene.vertices), Descriptor::storage(scene.previous), Descriptor::storage(stages_),
                     Descriptor::storage(scene.triangles), Descriptor::storage(scene.indices), Descriptor::storage(scene.emissive)});
  vertices_.bind(cmd);
  vertices_.push_descriptors(cmd, d);
  vertices_.push_constants(cmd, float(frame_seconds));
  vkCmdDispatchIndirect(cmd, indirect_.handle(), GIQ_PARTICLES_VERTICES_ARGS * sizeof(uint32_t));
  full_barrier(cmd);
}

ParticleSystem::Counts ParticleSystem::counts() const {
  const std::vector<uint8_t> b = counters_.download();
  uint32_t c[4];
  std::memcpy(c, b.data(), sizeof(c));
  return {c[GIQ_PARTICLES_OUT], c[GIQ_PARTICLES_DEAD], c[GIQ_PARTICLES_EMIT]};
}

std::vector<ParticleSystem::State> ParticleSystem::alive() const {
  const Counts c = counts();
  // The list written last is the one the next frame reads: alive_[1 - out_].
  const std::vector<uint8_t> list = alive_[1 - out_].download(), all = particles_.download();
  std::vector<State> out;
  for (uint32_t i = 0; i < c.alive; ++i) {
    uint32_t slot;
    std::memcpy(&slot, list.data() + 4 * i, 4);
    gpu::GpuParticle p;
    std::memcpy(&p, all.data() + uint64_t(slot) * sizeof(p), sizeof(p));
    uint32_t id, stage;
    std::memcpy(&id, &p.birth_position.w, sizeof id);
    std::memcpy(&stage, &p.velocity.w, sizeof stage);
    out.push_back({slot, id, stage, glm::vec3(p.position), glm::vec3(p.velocity), p.position.w});
  }
  return out;
}

std::vector<uint32_t> ParticleSystem::dead_slots() const {
  const Counts c = counts();
  const std::vector<uint8_t> b = dead_.download();
  std::vector<uint32_t> out(c.dead);
  std::memcpy(out.data(), b.data(), c.dead * sizeof(uint32_t));
  return out;
}

}  // namespace giq::realtime
