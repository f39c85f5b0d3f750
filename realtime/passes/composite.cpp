#include "passes/composite.h"

#include <glm/vec2.hpp>

#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"

namespace giq::realtime {

CompositePass::CompositePass(Context& ctx, ShaderCompiler& compiler, uint32_t width, uint32_t height)
    : width_(width), height_(height),
      beauty_(ctx, {width, height, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT}) {
  pipeline_ = Pipeline::compute(ctx, compiler.compile("passes/composite.comp"),
                                {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                                 VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                                sizeof(glm::uvec2));
}

void CompositePass::record(VkCommandBuffer cmd, Image& direct, Image& indirect, GpuTimer& timer) {
  timer.begin(cmd, "composite");
  beauty_.transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
  pipeline_.bind(cmd);
  pipeline_.push_descriptors(cmd, {Descriptor::storage_image(direct), Descriptor::storage_image(indirect),
                                   Descriptor::storage_image(beauty_)});
  const glm::uvec2 size(width_, height_);
  pipeline_.push_constants(cmd, size);
  pipeline_.dispatch_2d(cmd, width_, height_);
  full_barrier(cmd);
  timer.end(cmd);
}

}  // namespace giq::realtime
