#include "techniques/vct/volume.h"

#include <cstring>
#include <utility>

#include "giq/realtime/context.h"
#include "giq/realtime/vk.h"

namespace giq::realtime {

Volume::Volume(Context& ctx, uint32_t size, uint32_t levels)
    : ctx_(&ctx), size_(size), levels_(levels) {
  // Both formats are 32-bit, so they are view-compatible under MUTABLE_FORMAT; the sRGB view
  // is restricted to sampling (sRGB formats have no storage support).
  const VkFormat formats[2] = {VK_FORMAT_R32_UINT, VK_FORMAT_R8G8B8A8_SRGB};
  VkImageFormatListCreateInfo list{VK_STRUCTURE_TYPE_IMAGE_FORMAT_LIST_CREATE_INFO};
  list.viewFormatCount = 2;
  list.pViewFormats = formats;
  VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ci.pNext = &list;
  ci.flags = VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT | VK_IMAGE_CREATE_EXTENDED_USAGE_BIT;
  ci.imageType = VK_IMAGE_TYPE_3D;
  ci.format = VK_FORMAT_R32_UINT;
  ci.extent = {size, size, size};
  ci.mipLevels = levels;
  ci.arrayLayers = 1;
  ci.samples = VK_SAMPLE_COUNT_1_BIT;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  vk_check(vkCreateImage(ctx.device(), &ci, nullptr, &image_), "vkCreateImage");
  try {
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(ctx.device(), image_, &req);
    alloc_ = ctx.allocator().allocate(req, MemoryUsage::Device, false);
    vk_check(vkBindImageMemory(ctx.device(), image_, alloc_.memory, alloc_.offset),
             "vkBindImageMemory");

    VkImageViewUsageCreateInfo sampled_usage{VK_STRUCTURE_TYPE_IMAGE_VIEW_USAGE_CREATE_INFO};
    sampled_usage.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.pNext = &sampled_usage;
    vi.image = image_;
    vi.viewType = VK_IMAGE_VIEW_TYPE_3D;
    vi.format = VK_FORMAT_R8G8B8A8_SRGB;
    vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, levels, 0, 1};
    vk_check(vkCreateImageView(ctx.device(), &vi, nullptr, &sampled_view_), "vkCreateImageView");

    VkImageViewUsageCreateInfo storage_usage{VK_STRUCTURE_TYPE_IMAGE_VIEW_USAGE_CREATE_INFO};
    storage_usage.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    vi.pNext = &storage_usage;
    vi.format = VK_FORMAT_R32_UINT;
    for (uint32_t l = 0; l < levels; ++l) {
      vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, l, 1, 0, 1};
      VkImageView v;
      vk_check(vkCreateImageView(ctx.device(), &vi, nullptr, &v), "vkCreateImageView");
      level_views_.push_back(v);
    }

    VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    si.magFilter = si.minFilter = VK_FILTER_LINEAR;
    si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    // Cones that leave the cube see nothing: transparent black, not a smeared border.
    si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    si.borderColor = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
    si.maxLod = float(levels);
    vk_check(vkCreateSampler(ctx.device(), &si, nullptr, &sampler_), "vkCreateSampler");
  } catch (...) {
    release();
    throw;
  }
}

Volume::~Volume() {
  release();
}

void Volume::release() {
  if (!ctx_) return;
  VkDevice d = ctx_->device();
  if (sampler_) vkDestroySampler(d, sampler_, nullptr);
  for (auto v : level_views_) vkDestroyImageView(d, v, nullptr);
  level_views_.clear();
  if (sampled_view_) vkDestroyImageView(d, sampled_view_, nullptr);
  if (image_) vkDestroyImage(d, image_, nullptr);
  ctx_->allocator().free(alloc_);
  sampler_ = VK_NULL_HANDLE, sampled_view_ = VK_NULL_HANDLE, image_ = VK_NULL_HANDLE,
  ctx_ = nullptr;
}

Volume::Volume(Volume&& o) noexcept {
  *this = std::move(o);
}

Volume& Volume::operator=(Volume&& o) noexcept {
  if (this != &o) {
    release();
    ctx_ = std::exchange(o.ctx_, nullptr);
    image_ = std::exchange(o.image_, VK_NULL_HANDLE);
    sampled_view_ = std::exchange(o.sampled_view_, VK_NULL_HANDLE);
    level_views_ = std::move(o.level_views_);
    o.level_views_.clear();
    sampler_ = std::exchange(o.sampler_, VK_NULL_HANDLE);
    alloc_ = std::exchange(o.alloc_, {});
    size_ = o.size_;
    levels_ = o.levels_;
    layout_ = o.layout_;
  }
  return *this;
}

Descriptor Volume::storage(uint32_t level) const {
  Descriptor d;
  d.type = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  d.image = {VK_NULL_HANDLE, level_views_.at(level), VK_IMAGE_LAYOUT_GENERAL};
  return d;
}

Descriptor Volume::sampled() const {
  Descriptor d;
  d.type = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  d.image = {sampler_, sampled_view_, VK_IMAGE_LAYOUT_GENERAL};
  return d;
}

void Volume::make_general(VkCommandBuffer cmd) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  b.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
  b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  b.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  b.oldLayout = layout_;
  b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image_;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, levels_, 0, 1};
  VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  di.imageMemoryBarrierCount = 1;
  di.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &di);
  layout_ = VK_IMAGE_LAYOUT_GENERAL;
}

}  // namespace giq::realtime
