#pragma once
// GPU buffers and images placed in the sub-allocator, staging uploads and read-back, and the
// barriers between passes. Every resource is move-only and frees itself.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

#include "giq/realtime/allocator.h"

namespace giq::realtime {

class Context;

class Buffer {
 public:
  Buffer() = default;
  Buffer(Context& ctx, uint64_t size, VkBufferUsageFlags usage, MemoryUsage memory = MemoryUsage::Device);
  ~Buffer();
  Buffer(Buffer&& o) noexcept;
  Buffer& operator=(Buffer&& o) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  // A device-local storage buffer holding `bytes` (at least 16 bytes, so empty scene arrays
  // still bind), filled through a staging buffer.
  static Buffer storage(Context& ctx, const void* data, uint64_t bytes, VkBufferUsageFlags extra = 0);
  template <class T>
  static Buffer storage(Context& ctx, const std::vector<T>& v, VkBufferUsageFlags extra = 0) {
    return storage(ctx, v.data(), v.size() * sizeof(T), extra);
  }

  VkBuffer handle() const { return buffer_; }
  uint64_t size() const { return size_; }
  void* mapped() const { return alloc_.mapped; }
  explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }
  // The buffer's device address, for shaders that read it through GL_EXT_buffer_reference;
  // the buffer needs VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT.
  VkDeviceAddress address() const;

  // Copies host data in: directly when mapped, else through a staging buffer (blocking).
  void upload(const void* data, uint64_t bytes, uint64_t offset = 0);
  // Copies the given byte ranges of `image` (the whole buffer's contents as the host holds
  // them) to the same offsets, leaving the rest as it is; one staging copy when not mapped.
  void upload_ranges(const void* image, const std::vector<VkBufferCopy>& ranges);
  // Copies each range's bytes from `packed` (`packed_bytes` long: pieces gathered one after
  // another) at its srcOffset to its dstOffset, leaving the rest as it is; one staging copy of
  // the pieces alone when not mapped.
  void upload_pieces(const void* packed, uint64_t packed_bytes, const std::vector<VkBufferCopy>& ranges);
  // Copies the buffer out (blocking; through a read-back buffer when not mapped).
  std::vector<uint8_t> download() const;

 private:
  void release();
  Context* ctx_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  Allocation alloc_;
  uint64_t size_ = 0;
};

struct ImageDesc {
  uint32_t width = 1, height = 1, layers = 1;
  VkFormat format = VK_FORMAT_R32G32B32A32_SFLOAT;
  VkImageUsageFlags usage = 0;
  bool array = false;  // a 2D-array view even for one layer (shaders that index layers)
  uint32_t depth = 1;   // > 1: a 3D image (one layer)
  uint32_t levels = 1;  // mip levels
  // A format of the same texel size the image is also read in (MUTABLE_FORMAT): view() then
  // samples through it (all levels), while level_view() keeps `format` for storage. For
  // example R32_UINT written with atomics and read as R8G8B8A8_SRGB, which the hardware
  // decodes before it filters.
  VkFormat sampled_format = VK_FORMAT_UNDEFINED;
};

class Image {
 public:
  Image() = default;
  Image(Context& ctx, const ImageDesc& desc);
  ~Image();
  Image(Image&& o) noexcept;
  Image& operator=(Image&& o) noexcept;
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;

  VkImage handle() const { return image_; }
  VkImageView view() const { return view_; }              // all layers (2D array when layers > 1 or desc.array)
  VkImageView layer_view(uint32_t layer) const { return layer_views_.at(layer); }
  VkImageView level_view(uint32_t level) const { return level_views_.at(level); }  // in `format`
  const ImageDesc& desc() const { return desc_; }
  VkImageAspectFlags aspect() const;
  VkImageLayout layout() const { return layout_; }
  explicit operator bool() const { return image_ != VK_NULL_HANDLE; }

  // Moves the image to `layout`, waiting for every earlier command. Passes in giq are few and
  // large, so a full barrier costs little and cannot be wrong.
  void transition(VkCommandBuffer cmd, VkImageLayout layout);
  // Clears a colour image to `value` (leaves it in GENERAL layout).
  void clear(VkCommandBuffer cmd, const float value[4]);

  // Reads an RGBA32F or R32 image back (blocking): width*height*components floats, row-major.
  // Other 32-bit formats come back as their bits; RGBA16F as its halves, two to a float.
  std::vector<float> read_floats(uint32_t layer = 0);
  // Fills a layer from host data of the same layout (blocking); leaves the image GENERAL.
  void write_floats(const std::vector<float>& data, uint32_t layer = 0);

 private:
  void release();
  Context* ctx_ = nullptr;
  VkImage image_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  std::vector<VkImageView> layer_views_, level_views_;
  Allocation alloc_;
  ImageDesc desc_;
  VkImageLayout layout_ = VK_IMAGE_LAYOUT_UNDEFINED;
};

// Makes every earlier shader/transfer write visible to every later read or write.
void full_barrier(VkCommandBuffer cmd);
// Makes earlier compute-shader writes visible to later compute-shader reads and writes only:
// for chains of dependent dispatches (propagation steps), where a full barrier's wider scope
// (every stage, the host) costs time on every link.
void compute_barrier(VkCommandBuffer cmd);

// A sampler object: linear or nearest filtering, clamp to edge, optional depth compare
// (for PCF shadow lookups); or, for mipmapped volumes, trilinear with linear blending between
// `max_lod` + 1 levels and transparent black outside (so that what leaves the volume sees
// nothing, not a smeared border).
class Sampler {
 public:
  Sampler() = default;
  Sampler(Context& ctx, bool linear, bool depth_compare);
  static Sampler trilinear_transparent(Context& ctx, float max_lod);
  ~Sampler();
  Sampler(Sampler&& o) noexcept : device_(o.device_), sampler_(o.sampler_) { o.sampler_ = VK_NULL_HANDLE; }
  Sampler& operator=(Sampler&& o) noexcept;
  Sampler(const Sampler&) = delete;
  VkSampler handle() const { return sampler_; }

 private:
  Sampler(Context& ctx, const VkSamplerCreateInfo& ci);
  VkDevice device_ = VK_NULL_HANDLE;
  VkSampler sampler_ = VK_NULL_HANDLE;
};

}  // namespace giq::realtime
