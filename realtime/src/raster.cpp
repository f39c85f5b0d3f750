#include "giq/realtime/raster.h"

#include "giq/realtime/scene_gpu.h"

namespace giq::realtime {

void begin_rendering(VkCommandBuffer cmd, uint32_t width, uint32_t height, const RenderTargets& targets,
                     VkExtent2D viewport) {
  std::vector<VkRenderingAttachmentInfo> colors(targets.colors.size());
  for (size_t i = 0; i < colors.size(); ++i) {
    colors[i] = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    colors[i].imageView = targets.colors[i];
    colors[i].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colors[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    colors[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    colors[i].clearValue = {};
  }
  VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depth.imageView = targets.depth;
  depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  depth.storeOp = targets.store_depth ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
  depth.clearValue.depthStencil = {1.0f, 0};
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, {width, height}};
  ri.layerCount = 1;
  ri.colorAttachmentCount = uint32_t(colors.size());
  ri.pColorAttachments = colors.data();
  ri.pDepthAttachment = targets.depth != VK_NULL_HANDLE ? &depth : nullptr;
  vkCmdBeginRendering(cmd, &ri);
  if (viewport.width == 0) viewport = {width, height};
  const VkViewport vp{0.0f, 0.0f, float(viewport.width), float(viewport.height), 0.0f, 1.0f};
  const VkRect2D sc{{0, 0}, viewport};
  vkCmdSetViewport(cmd, 0, 1, &vp);
  vkCmdSetScissor(cmd, 0, 1, &sc);
}

void draw_scene(VkCommandBuffer cmd, const SceneGpu& scene) {
  if (scene.triangle_count() == 0) return;
  vkCmdBindIndexBuffer(cmd, scene.index_buffer().handle(), 0, VK_INDEX_TYPE_UINT32);
  vkCmdDrawIndexed(cmd, 3 * scene.triangle_count(), 1, 0, 0, 0);
}

}  // namespace giq::realtime
