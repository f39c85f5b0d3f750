#pragma once
// The raster passes' common steps (G-buffer, shadow maps, reflective shadow maps): one
// dynamic-rendering pass over the whole target, then every scene triangle drawn once.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace giq::realtime {

class SceneGpu;

struct RenderTargets {
  std::vector<VkImageView> colors;  // COLOR_ATTACHMENT_OPTIMAL; cleared to zero, stored
  VkImageView depth = VK_NULL_HANDLE;  // DEPTH_ATTACHMENT_OPTIMAL; cleared to 1
  bool store_depth = false;            // keep the depth (shadow maps), or discard it
};

// Begins rendering into `targets`, cleared over width x height, drawn through a viewport and
// scissor of `viewport` texels from the corner (0: the whole width x height); end with
// vkCmdEndRendering.
void begin_rendering(VkCommandBuffer cmd, uint32_t width, uint32_t height, const RenderTargets& targets,
                     VkExtent2D viewport = {0, 0});
// Draws every triangle of the scene with the bound graphics pipeline (nothing for an empty scene).
void draw_scene(VkCommandBuffer cmd, const SceneGpu& scene);

}  // namespace giq::realtime
