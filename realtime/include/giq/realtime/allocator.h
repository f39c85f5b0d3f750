#pragma once
// Device memory sub-allocation. Drivers limit the number of live vkAllocateMemory objects
// (maxMemoryAllocationCount may be as low as 4096) and each call is slow, so giq allocates
// large blocks and places every buffer and image inside one of them.
//
// RangeAllocator is the pure bookkeeping (first-fit over a free list with coalescing), unit
// tested without a device. MemoryAllocator owns the VkDeviceMemory blocks, one pool per
// (memory type, linear or optimal tiling): keeping buffers and optimally tiled images in
// separate blocks satisfies bufferImageGranularity without padding.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <vector>

namespace giq::realtime {

class RangeAllocator {
 public:
  explicit RangeAllocator(uint64_t capacity);

  // Offset of a free range of `size` bytes aligned to `alignment` (a power of two), or
  // nothing when no free range is large enough. size 0 is treated as 1.
  std::optional<uint64_t> allocate(uint64_t size, uint64_t alignment);
  // Returns a range obtained from allocate (same offset and size); merges it with free
  // neighbours. Throws std::logic_error on a range that is not allocated.
  void free(uint64_t offset, uint64_t size);

  uint64_t capacity() const { return capacity_; }
  uint64_t used() const { return used_; }
  size_t free_range_count() const { return free_.size(); }
  uint64_t largest_free_range() const;

 private:
  uint64_t capacity_;
  uint64_t used_ = 0;
  std::map<uint64_t, uint64_t> free_;       // offset -> size, disjoint and non-adjacent
  std::map<uint64_t, uint64_t> allocated_;  // offset -> size as returned to the caller
};

struct Allocation {
  VkDeviceMemory memory = VK_NULL_HANDLE;
  uint64_t offset = 0;
  uint64_t size = 0;
  void* mapped = nullptr;  // host pointer at `offset` for host-visible memory, else null
  int pool = -1;
  int block = -1;
  explicit operator bool() const { return memory != VK_NULL_HANDLE; }
};

enum class MemoryUsage {
  Device,    // DEVICE_LOCAL; not mapped
  Upload,    // HOST_VISIBLE | HOST_COHERENT, mapped; staging and per-frame constants
  Readback,  // HOST_VISIBLE | HOST_COHERENT (HOST_CACHED preferred), mapped
};

class MemoryAllocator {
 public:
  static constexpr uint64_t kBlockSize = 64ull << 20;

  MemoryAllocator(VkDevice device, VkPhysicalDevice physical);
  ~MemoryAllocator();
  MemoryAllocator(const MemoryAllocator&) = delete;
  MemoryAllocator& operator=(const MemoryAllocator&) = delete;

  Allocation allocate(const VkMemoryRequirements& req, MemoryUsage usage, bool linear);
  void free(Allocation& a);

  // Number of VkDeviceMemory objects alive and bytes handed out, for tests and reports.
  size_t block_count() const;
  uint64_t bytes_in_use() const;

 private:
  struct Block {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;
    std::unique_ptr<RangeAllocator> ranges;
  };
  struct Pool {
    uint32_t type = 0;
    bool linear = true;
    std::vector<Block> blocks;
  };
  uint32_t choose_type(uint32_t type_bits, MemoryUsage usage) const;

  VkDevice device_;
  VkPhysicalDeviceMemoryProperties props_{};
  std::vector<Pool> pools_;
};

}  // namespace giq::realtime
