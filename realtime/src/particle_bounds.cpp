#include "giq/realtime/particle_bounds.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include "giq/realtime/context.h"
#include "giq/realtime/shader.h"

namespace giq::realtime {

namespace {
constexpr uint32_t kChunk = 4096;  // particles a group reduces (GIQ_BOUNDS_CHUNK)
}

ParticleBounds::ParticleBounds(Context& ctx, ShaderCompiler& compiler)
    : ctx_(&ctx),
      pipeline_(Pipeline::compute(ctx, compiler.compile("shaders/particle_bounds.comp"),
                                  std::vector<VkDescriptorType>(7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER), 2 * sizeof(uint32_t))) {}

void ParticleBounds::record(VkCommandBuffer cmd, const Buffer& vertices, const std::vector<Range>& ranges,
                            const std::vector<glm::vec4>& points) {
  std::vector<glm::uvec4> chunks;
  stage_rows_.clear();
  points_count_ = uint32_t(points.size());
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
  fit(points_, std::max<uint64_t>(1, points.size()) * sizeof(glm::vec4));
  fit(nearest_, std::max<uint64_t>(1, chunks.size() * points.size()) * sizeof(float));
  chunks_.upload(chunks.data(), chunks.size() * sizeof(glm::uvec4));
  stages_.upload(stage_rows_.data(), stage_rows_.size() * sizeof(glm::uvec4));
  if (!points.empty()) points_.upload(points.data(), points.size() * sizeof(glm::vec4));
  pipeline_.bind(cmd);
  pipeline_.push_descriptors(cmd, {Descriptor::storage(vertices), Descriptor::storage(chunks_), Descriptor::storage(stages_),
                                   Descriptor::storage(partials_), Descriptor::storage(results_), Descriptor::storage(points_),
                                   Descriptor::storage(nearest_)});
  const uint32_t groups[3] = {uint32_t(chunks.size()), uint32_t(stage_rows_.size()), uint32_t(chunks.size())};
  for (uint32_t phase = 0; phase < 3; ++phase) {
    const uint32_t push[2] = {phase, points_count_};
    pipeline_.push_constants(cmd, push);
    vkCmdDispatch(cmd, groups[phase], 1, 1);
    full_barrier(cmd);
  }
}

std::vector<ParticleBounds::Stage> ParticleBounds::read() const {
  std::vector<Stage> out(stage_rows_.size());
  if (stage_rows_.empty() || !results_) return out;
  const std::vector<uint8_t> r = results_.download(), p = partials_.download();
  const std::vector<uint8_t> n = points_count_ ? nearest_.download() : std::vector<uint8_t>();
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
    // (The shader starts each point's minimum at 3e38, which a w 0 point keeps.)
    o.nearest.assign(points_count_, std::numeric_limits<float>::infinity());
    for (uint32_t c = st.x; c < st.x + st.y; ++c)
      for (uint32_t k = 0; k < points_count_; ++k) {
        float d;
        std::memcpy(&d, n.data() + (size_t(c) * points_count_ + k) * sizeof(float), sizeof(d));
        if (d < 1.0e38f) o.nearest[k] = std::min(o.nearest[k], d);
      }
  }
  return out;
}

}  // namespace giq::realtime
