#include "passes/upsample.h"

#include "giq/base/error.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"
#include "passes/gbuffer.h"
#include "passes/upsample_shared.h"

namespace giq::realtime {

std::vector<Parameter> UpsamplePass::parameters(int default_k) {
  return {{"downsample", double(default_k), 1, 8, true,
           "k: indirect light is computed at 1/k of the resolution per axis, then upsampled edge-aware"},
          {"blur", 1, 0, 1, true, "1: 9x9 cross-bilateral blur after the upsample"}};
}

UpsamplePass::UpsamplePass(Context& ctx, ShaderCompiler& compiler, uint32_t width, uint32_t height, uint32_t k,
                           bool blur)
    : width_(width), height_(height), k_(k), blur_(blur) {
  if (k < 1 || k > 8) throw InputError("", "--param downsample", std::to_string(k) + "; expected 1..8");
  const ImageDesc d{width, height, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT};
  output_ = Image(ctx, d);
  if (blur_) scratch_ = Image(ctx, d);
  pipeline_ = Pipeline::compute(ctx, compiler.compile("passes/upsample.comp"),
                                std::vector<VkDescriptorType>(4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE),
                                sizeof(gpu::UpsamplePush));
}

UpsamplePass::UpsamplePass(const TechniqueCreateInfo& ci)
    : UpsamplePass(ci.ctx, ci.compiler, ci.width, ci.height, uint32_t(ci.parameters.get_int("downsample")),
                   ci.parameters.get_int("blur") != 0) {}

void UpsamplePass::dispatch(VkCommandBuffer cmd, GBufferPass& gbuffer, Image& src, Image& dst, uint32_t mode) {
  dst.transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
  pipeline_.bind(cmd);
  pipeline_.push_descriptors(cmd, {Descriptor::storage_image(gbuffer.position()),
                                   Descriptor::storage_image(gbuffer.normal()), Descriptor::storage_image(src),
                                   Descriptor::storage_image(dst)});
  pipeline_.push_constants(cmd, gpu::UpsamplePush{glm::uvec2(width_, height_), k_, mode});
  pipeline_.dispatch_2d(cmd, width_, height_);
  full_barrier(cmd);
}

void UpsamplePass::record(VkCommandBuffer cmd, Image& low, GBufferPass& gbuffer, GpuTimer& timer) {
  timer.begin(cmd, "upsample");
  dispatch(cmd, gbuffer, low, output_, GIQ_UPSAMPLE_MODE_UPSAMPLE);
  timer.end(cmd);
  if (!blur_) return;
  timer.begin(cmd, "blur");
  dispatch(cmd, gbuffer, output_, scratch_, GIQ_UPSAMPLE_MODE_BLUR_X);
  dispatch(cmd, gbuffer, scratch_, output_, GIQ_UPSAMPLE_MODE_BLUR_Y);
  timer.end(cmd);
}

}  // namespace giq::realtime
