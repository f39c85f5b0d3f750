#include "giq/realtime/resources.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "giq/realtime/context.h"
#include "giq/realtime/vk.h"

namespace giq::realtime {

Buffer::Buffer(Context& ctx, uint64_t size, VkBufferUsageFlags usage, MemoryUsage memory)
    : ctx_(&ctx), size_(size) {
  VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  ci.size = size;
  ci.usage = usage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  vk_check(vkCreateBuffer(ctx.device(), &ci, nullptr, &buffer_), "vkCreateBuffer");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device(), buffer_, &req);
  try {
    alloc_ = ctx.allocator().allocate(req, memory, true);
    vk_check(vkBindBufferMemory(ctx.device(), buffer_, alloc_.memory, alloc_.offset), "vkBindBufferMemory");
  } catch (...) {
    release();
    throw;
  }
}

Buffer::~Buffer() { release(); }

void Buffer::release() {
  if (!ctx_) return;
  if (buffer_) vkDestroyBuffer(ctx_->device(), buffer_, nullptr);
  ctx_->allocator().free(alloc_);
  buffer_ = VK_NULL_HANDLE;
  ctx_ = nullptr;
}

Buffer::Buffer(Buffer&& o) noexcept
    : ctx_(std::exchange(o.ctx_, nullptr)), buffer_(std::exchange(o.buffer_, VK_NULL_HANDLE)),
      alloc_(std::exchange(o.alloc_, {})), size_(o.size_) {}

Buffer& Buffer::operator=(Buffer&& o) noexcept {
  if (this != &o) {
    release();
    ctx_ = std::exchange(o.ctx_, nullptr);
    buffer_ = std::exchange(o.buffer_, VK_NULL_HANDLE);
    alloc_ = std::exchange(o.alloc_, {});
    size_ = o.size_;
  }
  return *this;
}

Buffer Buffer::storage(Context& ctx, const void* data, uint64_t bytes, VkBufferUsageFlags extra) {
  Buffer b(ctx, std::max<uint64_t>(bytes, 16), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | extra);
  if (bytes > 0) b.upload(data, bytes);
  return b;
}

VkDeviceAddress Buffer::address() const {
  VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
  info.buffer = buffer_;
  return vkGetBufferDeviceAddress(ctx_->device(), &info);
}

void Buffer::upload(const void* data, uint64_t bytes, uint64_t offset) {
  if (offset + bytes > size_) throw std::logic_error("Buffer::upload past the end of the buffer");
  if (alloc_.mapped) {
    std::memcpy(static_cast<char*>(alloc_.mapped) + offset, data, bytes);
    return;
  }
  Buffer staging(*ctx_, bytes, 0, MemoryUsage::Upload);
  std::memcpy(staging.mapped(), data, bytes);
  ctx_->submit_and_wait([&](VkCommandBuffer cmd) {
    VkBufferCopy c{0, offset, bytes};
    vkCmdCopyBuffer(cmd, staging.handle(), buffer_, 1, &c);
  });
}

void Buffer::upload_ranges(const void* image, const std::vector<VkBufferCopy>& ranges) {
  uint64_t end = 0;
  for (const VkBufferCopy& r : ranges) {
    if (r.srcOffset != r.dstOffset) throw std::logic_error("Buffer::upload_ranges: a range moved");
    end = std::max(end, r.dstOffset + r.size);
  }
  upload_pieces(image, end, ranges);
}

void Buffer::upload_pieces(const void* packed, uint64_t packed_bytes, const std::vector<VkBufferCopy>& given) {
  std::vector<VkBufferCopy> ranges;  // without empty ones, which a copy command may not hold
  for (const VkBufferCopy& r : given) {
    if (r.dstOffset + r.size > size_ || r.srcOffset + r.size > packed_bytes) throw std::logic_error("Buffer::upload_pieces: a range past the end");
    if (r.size > 0) ranges.push_back(r);
  }
  if (ranges.empty()) return;
  const char* bytes = static_cast<const char*>(packed);
  if (alloc_.mapped) {
    for (const VkBufferCopy& r : ranges) std::memcpy(static_cast<char*>(alloc_.mapped) + r.dstOffset, bytes + r.srcOffset, r.size);
    return;
  }
  // Only the ranges' bytes are staged, at their offsets in `packed`.
  Buffer staging(*ctx_, packed_bytes, 0, MemoryUsage::Upload);
  for (const VkBufferCopy& r : ranges) std::memcpy(static_cast<char*>(staging.mapped()) + r.srcOffset, bytes + r.srcOffset, r.size);
  ctx_->submit_and_wait([&](VkCommandBuffer cmd) { vkCmdCopyBuffer(cmd, staging.handle(), buffer_, uint32_t(ranges.size()), ranges.data()); });
}

std::vector<uint8_t> Buffer::download() const {
  std::vector<uint8_t> out(size_);
  if (alloc_.mapped) {
    std::memcpy(out.data(), alloc_.mapped, size_);
    return out;
  }
  Buffer rb(*ctx_, size_, 0, MemoryUsage::Readback);
  ctx_->submit_and_wait([&](VkCommandBuffer cmd) {
    full_barrier(cmd);
    VkBufferCopy c{0, 0, size_};
    vkCmdCopyBuffer(cmd, buffer_, rb.handle(), 1, &c);
  });
  std::memcpy(out.data(), rb.mapped(), size_);
  return out;
}

namespace {
bool is_depth(VkFormat f) {
  return f == VK_FORMAT_D32_SFLOAT || f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_D24_UNORM_S8_UINT ||
         f == VK_FORMAT_D32_SFLOAT_S8_UINT;
}
uint32_t texel_bytes(VkFormat f) {
  switch (f) {
    case VK_FORMAT_R32G32B32A32_SFLOAT:
    case VK_FORMAT_R32G32B32A32_UINT: return 16;
    case VK_FORMAT_R16G16B16A16_SFLOAT: return 8;
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_D32_SFLOAT: return 4;
    default: throw std::logic_error("read-back of this image format is not supported");
  }
}
}  // namespace

VkImageAspectFlags Image::aspect() const {
  return is_depth(desc_.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}

Image::Image(Context& ctx, const ImageDesc& desc) : ctx_(&ctx), desc_(desc) {
  const bool volume = desc.depth > 1;
  const bool mutable_format = desc.sampled_format != VK_FORMAT_UNDEFINED;
  const VkFormat formats[2] = {desc.format, desc.sampled_format};
  VkImageFormatListCreateInfo list{VK_STRUCTURE_TYPE_IMAGE_FORMAT_LIST_CREATE_INFO};
  list.viewFormatCount = 2;
  list.pViewFormats = formats;
  VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  if (mutable_format) {
    // The sampled format may lack storage support (sRGB formats do): each view declares the
    // usage it needs.
    ci.pNext = &list;
    ci.flags = VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT | VK_IMAGE_CREATE_EXTENDED_USAGE_BIT;
  }
  ci.imageType = volume ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
  ci.format = desc.format;
  ci.extent = {desc.width, desc.height, desc.depth};
  ci.mipLevels = desc.levels;
  ci.arrayLayers = desc.layers;
  ci.samples = VK_SAMPLE_COUNT_1_BIT;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage = desc.usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  vk_check(vkCreateImage(ctx.device(), &ci, nullptr, &image_), "vkCreateImage");
  try {
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(ctx.device(), image_, &req);
    alloc_ = ctx.allocator().allocate(req, MemoryUsage::Device, false);
    vk_check(vkBindImageMemory(ctx.device(), image_, alloc_.memory, alloc_.offset), "vkBindImageMemory");
    VkImageViewUsageCreateInfo sampled_usage{VK_STRUCTURE_TYPE_IMAGE_VIEW_USAGE_CREATE_INFO};
    sampled_usage.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    VkImageViewUsageCreateInfo storage_usage{VK_STRUCTURE_TYPE_IMAGE_VIEW_USAGE_CREATE_INFO};
    storage_usage.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.pNext = mutable_format ? &sampled_usage : nullptr;
    vi.image = image_;
    vi.viewType = volume                         ? VK_IMAGE_VIEW_TYPE_3D
                  : desc.layers > 1 || desc.array ? VK_IMAGE_VIEW_TYPE_2D_ARRAY
                                                  : VK_IMAGE_VIEW_TYPE_2D;
    vi.format = mutable_format ? desc.sampled_format : desc.format;
    vi.subresourceRange = {aspect(), 0, desc.levels, 0, desc.layers};
    vk_check(vkCreateImageView(ctx.device(), &vi, nullptr, &view_), "vkCreateImageView");
    vi.pNext = mutable_format ? &storage_usage : nullptr;
    vi.format = desc.format;
    if (desc.levels > 1 || volume)
      for (uint32_t l = 0; l < desc.levels; ++l) {
        vi.subresourceRange = {aspect(), l, 1, 0, desc.layers};
        VkImageView v;
        vk_check(vkCreateImageView(ctx.device(), &vi, nullptr, &v), "vkCreateImageView");
        level_views_.push_back(v);
      }
    if (!volume)
      for (uint32_t l = 0; l < desc.layers; ++l) {
        vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
        vi.subresourceRange = {aspect(), 0, 1, l, 1};
        VkImageView v;
        vk_check(vkCreateImageView(ctx.device(), &vi, nullptr, &v), "vkCreateImageView");
        layer_views_.push_back(v);
      }
  } catch (...) {
    release();
    throw;
  }
}

Image::~Image() { release(); }

void Image::release() {
  if (!ctx_) return;
  for (auto v : layer_views_) vkDestroyImageView(ctx_->device(), v, nullptr);
  for (auto v : level_views_) vkDestroyImageView(ctx_->device(), v, nullptr);
  layer_views_.clear();
  level_views_.clear();
  if (view_) vkDestroyImageView(ctx_->device(), view_, nullptr);
  if (image_) vkDestroyImage(ctx_->device(), image_, nullptr);
  ctx_->allocator().free(alloc_);
  view_ = VK_NULL_HANDLE, image_ = VK_NULL_HANDLE, ctx_ = nullptr;
}

Image::Image(Image&& o) noexcept
    : ctx_(std::exchange(o.ctx_, nullptr)), image_(std::exchange(o.image_, VK_NULL_HANDLE)),
      view_(std::exchange(o.view_, VK_NULL_HANDLE)), layer_views_(std::move(o.layer_views_)),
      level_views_(std::move(o.level_views_)), alloc_(std::exchange(o.alloc_, {})), desc_(o.desc_),
      layout_(o.layout_) {
  o.layer_views_.clear();
  o.level_views_.clear();
}

Image& Image::operator=(Image&& o) noexcept {
  if (this != &o) {
    release();
    ctx_ = std::exchange(o.ctx_, nullptr);
    image_ = std::exchange(o.image_, VK_NULL_HANDLE);
    view_ = std::exchange(o.view_, VK_NULL_HANDLE);
    layer_views_ = std::move(o.layer_views_);
    o.layer_views_.clear();
    level_views_ = std::move(o.level_views_);
    o.level_views_.clear();
    alloc_ = std::exchange(o.alloc_, {});
    desc_ = o.desc_;
    layout_ = o.layout_;
  }
  return *this;
}

void Image::transition(VkCommandBuffer cmd, VkImageLayout layout) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  b.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
  b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  b.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  b.oldLayout = layout_;
  b.newLayout = layout;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image_;
  b.subresourceRange = {aspect(), 0, desc_.levels, 0, desc_.layers};
  VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  di.imageMemoryBarrierCount = 1;
  di.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &di);
  layout_ = layout;
}

void Image::clear(VkCommandBuffer cmd, const float value[4]) {
  transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
  VkClearColorValue c;
  std::memcpy(c.float32, value, sizeof c.float32);
  VkImageSubresourceRange r{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, desc_.layers};
  vkCmdClearColorImage(cmd, image_, VK_IMAGE_LAYOUT_GENERAL, &c, 1, &r);
}

std::vector<float> Image::read_floats(uint32_t layer) {
  const uint32_t bytes_per_texel = texel_bytes(desc_.format);
  const uint64_t bytes = uint64_t(desc_.width) * desc_.height * bytes_per_texel;
  Buffer rb(*ctx_, bytes, 0, MemoryUsage::Readback);
  const VkImageLayout previous = layout_;
  ctx_->submit_and_wait([&](VkCommandBuffer cmd) {
    transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    VkBufferImageCopy c{};
    c.imageSubresource = {aspect(), 0, layer, 1};
    c.imageExtent = {desc_.width, desc_.height, 1};
    vkCmdCopyImageToBuffer(cmd, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, rb.handle(), 1, &c);
    // Leave the image as the technique left it: reading it back is not a pass of its own.
    if (previous != VK_IMAGE_LAYOUT_UNDEFINED) transition(cmd, previous);
    full_barrier(cmd);
  });
  std::vector<float> out(bytes / sizeof(float));
  std::memcpy(out.data(), rb.mapped(), bytes);
  return out;
}

void Image::write_floats(const std::vector<float>& data, uint32_t layer) {
  const uint64_t bytes = uint64_t(desc_.width) * desc_.height * texel_bytes(desc_.format);
  if (data.size() * sizeof(float) != bytes) throw std::logic_error("Image::write_floats: size mismatch");
  Buffer staging(*ctx_, bytes, 0, MemoryUsage::Upload);
  std::memcpy(staging.mapped(), data.data(), bytes);
  ctx_->submit_and_wait([&](VkCommandBuffer cmd) {
    transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    VkBufferImageCopy c{};
    c.imageSubresource = {aspect(), 0, layer, 1};
    c.imageExtent = {desc_.width, desc_.height, 1};
    vkCmdCopyBufferToImage(cmd, staging.handle(), image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &c);
    transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
  });
}

void full_barrier(VkCommandBuffer cmd) {
  VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  b.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  b.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
  // HOST: read-back buffers are read by the CPU after the fence, which alone does not make
  // device writes visible to the host.
  b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT | VK_PIPELINE_STAGE_2_HOST_BIT;
  b.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT | VK_ACCESS_2_HOST_READ_BIT;
  VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  di.memoryBarrierCount = 1;
  di.pMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &di);
}

Sampler::Sampler(Context& ctx, const VkSamplerCreateInfo& ci) : device_(ctx.device()) {
  vk_check(vkCreateSampler(device_, &ci, nullptr, &sampler_), "vkCreateSampler");
}

Sampler::Sampler(Context& ctx, bool linear, bool depth_compare) : device_(ctx.device()) {
  VkSamplerCreateInfo ci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  ci.magFilter = ci.minFilter = linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
  ci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  ci.addressModeU = ci.addressModeV = ci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  ci.compareEnable = depth_compare;
  ci.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
  ci.maxLod = 0.0f;
  vk_check(vkCreateSampler(device_, &ci, nullptr, &sampler_), "vkCreateSampler");
}

Sampler Sampler::trilinear_transparent(Context& ctx, float max_lod) {
  VkSamplerCreateInfo ci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  ci.magFilter = ci.minFilter = VK_FILTER_LINEAR;
  ci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  ci.addressModeU = ci.addressModeV = ci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
  ci.borderColor = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
  ci.maxLod = max_lod;
  return Sampler(ctx, ci);
}

Sampler::~Sampler() {
  if (sampler_) vkDestroySampler(device_, sampler_, nullptr);
}

Sampler& Sampler::operator=(Sampler&& o) noexcept {
  if (this != &o) {
    if (sampler_) vkDestroySampler(device_, sampler_, nullptr);
    device_ = o.device_;
    sampler_ = std::exchange(o.sampler_, VK_NULL_HANDLE);
  }
  return *this;
}

void compute_barrier(VkCommandBuffer cmd) {
  VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  b.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  b.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
  b.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  b.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
  VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  di.memoryBarrierCount = 1;
  di.pMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &di);
}

}  // namespace giq::realtime
