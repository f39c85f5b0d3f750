#include "giq/realtime/particle_bounds.h"

#include <algorithm>
#include <cstring>

#include "giq/realtime/context.h"
#include "giq/realtime/shader.h"

namespace giq::realtime {

namespace {
constexpr uint32_t kChunk = 4096;  // particles a group reduces (GIQ_BOUNDS_CHUNK)
}

ParticleBounds::ParticleBounds(Context& ctx, ShaderCompiler& compiler)
    : ctx_(&ctx),
      pipeline_(Pipeline::compute(ctx, compiler.compile("shaders/particle_bounds.comp"),
                                  std::vector<VkDescriptorType>(5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER), sizeof(uint32_t))) {}

void ParticleBounds::record(VkCommandBuffer cmd, const Buffer& vertices, const std::vector<Range>& ranges) {
  std::vector<glm::uvec4> chunks;
  stage_rows_.clear();
  for (size_t s = 0; s < ranges.size(); ++s) {
    const Range& r = ranges[s];
    stage_rows_.emplace_back(uint32_t(chunks.size()), 0u, r.particles, 0u);
    for (uint32_t p = 0; p < r.particles; p += kChunk)
      chunks.emplace_back(r.first_vertex + 6 * p, std::min(kChunk, r.particles - p), uint32_t(s), 0u);
    stage_rows_.back().y = uint32_t(chunks.size()) - stage_rows_.back().x;
  }
  if (chunks.empty()) return;
  auto fit = [&](Buffer& b, uint64_t bytes) {
    if (b.size() < bytes) b = Buffer(*ctx_, 2 * bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  };
  fit(chunks_, chunks.size() * sizeof(glm::uvec4));
  fit(stages_, stage_rows_.size() * sizeof(glm::uvec4));
  fit(partials_, chunks.size() * 4 * sizeof(glm::vec4));
  fit(results_, stage_rows_.size() * 3 * sizeof(glm::vec4));
  chunks_.upload(chunks.data(), chunks.size() * sizeof(glm::uvec4));
  stages_.upload(stage_rows_.data(), stage_rows_.size() * sizeof(glm::uvec4));
  pipeline_.bind(cmd);
  pipeline_.push_descriptors(cmd, {Descriptor::storage(vertices), Descriptor::storage(chunks_), Descriptor::storage(stages_),
                                   Descriptor::storage(partials_), Descriptor::storage(results_)});
  const uint32_t groups[3] = {uint32_t(chunks.size()), uint32_t(stage_rows_.size()), uint32_t(chunks.size())};
  for (uint32_t phase = 0; phase < 3; ++phase) {
    pipeline_.push_constants(cmd, phase);
    vkCmdDispatch(cmd, groups[phase], 1, 1);
    full_barrier(cmd);
  }
}

std::vector<ParticleBounds::Stage> ParticleBounds::read() const {
  std::vector<Stage> out(stage_rows_.size());
  if (stage_rows_.empty() || !results_) return out;
  const std::vector<uint8_t> r = results_.download(), p = partials_.download();
  auto row = [](const std::vector<uint8_t>& b, size_t i) {
    glm::vec4 v;
    std::memcpy(&v, b.data() + i * sizeof(glm::vec4), sizeof(v));
    return v;
  };
  for (size_t s = 0; s < out.size(); ++s) {
    const glm::uvec4 st = stage_rows_[s];
    if (st.z == 0) continue;
    Stage& o = out[s];
    o.particles = st.z;
    o.centroid = glm::vec3(row(r, 3 * s));
    o.lo = glm::vec3(row(r, 3 * s + 1));
    o.hi = glm::vec3(row(r, 3 * s + 2));
    for (uint32_t c = st.x; c < st.x + st.y; ++c) o.extent = std::max(o.extent, row(p, 4 * size_t(c) + 3).x);
  }
  return out;
}

}  // namespace giq::realtime
