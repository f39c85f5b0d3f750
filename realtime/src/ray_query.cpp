#include "giq/realtime/ray_query.h"

#include <cstring>

#include "giq/realtime/context.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/scene_gpu.h"
#include "giq/realtime/shader.h"

namespace giq::realtime {

RayQuery::RayQuery(Context& ctx, ShaderCompiler& compiler, const SceneGpu& scene) : ctx_(ctx), scene_(scene) {
  auto bindings = SceneGpu::binding_types();
  bindings.push_back(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  bindings.push_back(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  // The scene's defines: alpha-masked scenes trace through their cut-outs.
  pipeline_ = Pipeline::compute(ctx, compiler.compile("shaders/ray_query.comp", feature_defines(scene.features())), bindings,
                                sizeof(uint32_t));
}

std::vector<QueryHit> RayQuery::trace(const std::vector<QueryRay>& rays) {
  if (rays.empty()) return {};
  Buffer in = Buffer::storage(ctx_, rays);
  Buffer out(ctx_, rays.size() * sizeof(QueryHit), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Readback);
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) {
    pipeline_.bind(cmd);
    auto d = scene_.descriptors();
    d.push_back(Descriptor::storage(in));
    d.push_back(Descriptor::storage(out));
    pipeline_.push_descriptors(cmd, d);
    const uint32_t n = uint32_t(rays.size());
    pipeline_.push_constants(cmd, n);
    vkCmdDispatch(cmd, (n + 63) / 64, 1, 1);
    full_barrier(cmd);
  });
  std::vector<QueryHit> hits(rays.size());
  std::memcpy(hits.data(), out.mapped(), hits.size() * sizeof(QueryHit));
  return hits;
}

}  // namespace giq::realtime
