#include "giq/realtime/allocator.h"

#include <stdexcept>
#include <string>

#include "giq/base/error.h"
#include "giq/realtime/vk.h"

namespace giq::realtime {

RangeAllocator::RangeAllocator(uint64_t capacity) : capacity_(capacity) {
  if (capacity > 0) free_[0] = capacity;
}

std::optional<uint64_t> RangeAllocator::allocate(uint64_t size, uint64_t alignment) {
  if (size == 0) size = 1;
  if (alignment == 0 || (alignment & (alignment - 1)) != 0)
    throw std::logic_error("alignment must be a power of two, got " + std::to_string(alignment));
  for (auto it = free_.begin(); it != free_.end(); ++it) {
    const uint64_t start = it->first, len = it->second;
    const uint64_t aligned = (start + alignment - 1) & ~(alignment - 1);
    if (aligned < start || aligned - start > len || len - (aligned - start) < size) continue;
    // Split the free range into [start, aligned) and [aligned + size, start + len).
    const uint64_t tail = start + len - (aligned + size);
    free_.erase(it);
    if (aligned > start) free_[start] = aligned - start;
    if (tail > 0) free_[aligned + size] = tail;
    allocated_[aligned] = size;
    used_ += size;
    return aligned;
  }
  return std::nullopt;
}

void RangeAllocator::free(uint64_t offset, uint64_t size) {
  if (size == 0) size = 1;
  auto a = allocated_.find(offset);
  if (a == allocated_.end() || a->second != size)
    throw std::logic_error("free of a range that is not allocated: offset " + std::to_string(offset) +
                           ", size " + std::to_string(size));
  allocated_.erase(a);
  used_ -= size;
  uint64_t start = offset, len = size;
  auto next = free_.lower_bound(offset);
  if (next != free_.end() && next->first == start + len) {
    len += next->second;
    next = free_.erase(next);
  }
  if (next != free_.begin()) {
    auto prev = std::prev(next);
    if (prev->first + prev->second == start) {
      start = prev->first;
      len += prev->second;
      free_.erase(prev);
    }
  }
  free_[start] = len;
}

uint64_t RangeAllocator::largest_free_range() const {
  uint64_t best = 0;
  for (const auto& [o, s] : free_) best = std::max(best, s);
  return best;
}

MemoryAllocator::MemoryAllocator(VkDevice device, VkPhysicalDevice physical) : device_(device) {
  vkGetPhysicalDeviceMemoryProperties(physical, &props_);
}

MemoryAllocator::~MemoryAllocator() {
  for (auto& p : pools_)
    for (auto& b : p.blocks)
      if (b.memory) vkFreeMemory(device_, b.memory, nullptr);
}

uint32_t MemoryAllocator::choose_type(uint32_t type_bits, MemoryUsage usage) const {
  VkMemoryPropertyFlags required = 0, preferred = 0;
  switch (usage) {
    case MemoryUsage::Device: preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT; break;
    case MemoryUsage::Upload:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      break;
    case MemoryUsage::Readback:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
      break;
  }
  int fallback = -1;
  for (uint32_t i = 0; i < props_.memoryTypeCount; ++i) {
    if (!(type_bits & (1u << i))) continue;
    const VkMemoryPropertyFlags f = props_.memoryTypes[i].propertyFlags;
    if ((f & required) != required) continue;
    if ((f & preferred) == preferred) return i;
    if (fallback < 0) fallback = int(i);
  }
  if (fallback < 0) throw std::runtime_error("no Vulkan memory type fits the resource");
  return uint32_t(fallback);
}

Allocation MemoryAllocator::allocate(const VkMemoryRequirements& req, MemoryUsage usage, bool linear) {
  const uint32_t type = choose_type(req.memoryTypeBits, usage);
  int pi = -1;
  for (size_t i = 0; i < pools_.size(); ++i)
    if (pools_[i].type == type && pools_[i].linear == linear) pi = int(i);
  if (pi < 0) {
    pools_.push_back({type, linear, {}});
    pi = int(pools_.size() - 1);
  }
  Pool& pool = pools_[pi];
  for (size_t bi = 0; bi < pool.blocks.size(); ++bi) {
    Block& b = pool.blocks[bi];
    if (!b.memory) continue;
    if (auto off = b.ranges->allocate(req.size, req.alignment)) {
      return {b.memory, *off, req.size, b.mapped ? static_cast<char*>(b.mapped) + *off : nullptr, pi, int(bi)};
    }
  }
  // A new block: the standard size, or exactly the request when it is larger.
  Block b;
  const uint64_t size = std::max<uint64_t>(kBlockSize, req.size);
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = size;
  ai.memoryTypeIndex = type;
  // Buffer memory may back buffers read through device addresses (Buffer::address).
  VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  if (linear) ai.pNext = &flags;
  // Running out of GPU memory is the size of the request (resolution, technique parameters,
  // scene), not a fault of giq: an input error that says what was asked for.
  const uint64_t heap = props_.memoryHeaps[props_.memoryTypes[type].heapIndex].size;
  auto asked = [&] {
    auto mib = [](uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; };
    return "a resource of " + mib(req.size) + " with " + mib(bytes_in_use()) + " in use, on a memory heap of " +
           mib(heap) + "; lower --width/--height or the technique's resolution parameters";
  };
  if (req.size > heap) throw InputError("", "GPU memory", "the render needs " + asked());
  const VkResult r = vkAllocateMemory(device_, &ai, nullptr, &b.memory);
  if (r == VK_ERROR_OUT_OF_DEVICE_MEMORY || r == VK_ERROR_OUT_OF_HOST_MEMORY)
    throw InputError("", "GPU memory", std::string(vk_result_name(r)) + " allocating " + asked());
  vk_check(r, "vkAllocateMemory");
  // Every host-visible block is mapped once: pools are keyed by memory type, so on a device
  // whose only type is both device-local and host-visible (lavapipe) staging and device
  // resources share blocks, and device buffers are then filled by plain copies.
  if (props_.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT)
    vk_check(vkMapMemory(device_, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
  b.ranges = std::make_unique<RangeAllocator>(size);
  const uint64_t off = *b.ranges->allocate(req.size, req.alignment);
  int bi = -1;
  for (size_t i = 0; i < pool.blocks.size() && bi < 0; ++i)
    if (!pool.blocks[i].memory) bi = int(i);
  if (bi < 0) {
    pool.blocks.push_back(std::move(b));
    bi = int(pool.blocks.size() - 1);
  } else {
    pool.blocks[bi] = std::move(b);
  }
  Block& nb = pool.blocks[bi];
  return {nb.memory, off, req.size, nb.mapped ? static_cast<char*>(nb.mapped) + off : nullptr, pi, bi};
}

void MemoryAllocator::free(Allocation& a) {
  if (!a) return;
  Block& b = pools_.at(a.pool).blocks.at(a.block);
  b.ranges->free(a.offset, a.size);
  // Give an empty block back to the driver unless it is the pool's only one: a renderer that
  // recreates its targets each run would otherwise churn vkAllocateMemory.
  size_t live = 0;
  for (const auto& x : pools_[a.pool].blocks) live += x.memory != VK_NULL_HANDLE;
  if (b.ranges->used() == 0 && live > 1) {
    vkFreeMemory(device_, b.memory, nullptr);
    b = Block{};
  }
  a = Allocation{};
}

size_t MemoryAllocator::block_count() const {
  size_t n = 0;
  for (const auto& p : pools_)
    for (const auto& b : p.blocks) n += b.memory != VK_NULL_HANDLE;
  return n;
}

uint64_t MemoryAllocator::bytes_in_use() const {
  uint64_t n = 0;
  for (const auto& p : pools_)
    for (const auto& b : p.blocks)
      if (b.memory) n += b.ranges->used();
  return n;
}

}  // namespace giq::realtime
