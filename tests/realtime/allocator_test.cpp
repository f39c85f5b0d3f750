#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "giq/base/error.h"
#include "giq/realtime/allocator.h"
#include "giq/realtime/resources.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

TEST(RangeAllocator, AlignsAndFillsExactly) {
  RangeAllocator r(1024);
  auto a = r.allocate(100, 1);
  auto b = r.allocate(100, 256);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(*a, 0u);
  EXPECT_EQ(*b, 256u);  // the next 256-aligned offset after [0, 100)
  EXPECT_EQ(r.used(), 200u);
  // The gap [100, 256) stays usable.
  auto c = r.allocate(156, 4);
  ASSERT_TRUE(c);
  EXPECT_EQ(*c, 100u);
  EXPECT_FALSE(r.allocate(1024, 1));
  auto d = r.allocate(1024 - 356, 1);
  ASSERT_TRUE(d);
  EXPECT_EQ(r.used(), 1024u);
  EXPECT_FALSE(r.allocate(1, 1));
}

TEST(RangeAllocator, FreeCoalescesNeighbours) {
  RangeAllocator r(300);
  auto a = *r.allocate(100, 1), b = *r.allocate(100, 1), c = *r.allocate(100, 1);
  r.free(a, 100);
  r.free(c, 100);
  EXPECT_EQ(r.free_range_count(), 2u);
  EXPECT_FALSE(r.allocate(200, 1));  // fragmented: two separate 100-byte holes
  r.free(b, 100);
  EXPECT_EQ(r.free_range_count(), 1u);
  EXPECT_EQ(r.largest_free_range(), 300u);
  EXPECT_EQ(r.used(), 0u);
}

TEST(RangeAllocator, RejectsBadFreesAndAlignments) {
  RangeAllocator r(64);
  auto a = *r.allocate(16, 16);
  EXPECT_THROW(r.free(a, 8), std::logic_error);   // wrong size
  EXPECT_THROW(r.free(32, 16), std::logic_error);  // never allocated
  EXPECT_THROW(r.allocate(8, 3), std::logic_error);
  r.free(a, 16);
  EXPECT_THROW(r.free(a, 16), std::logic_error);  // double free
}

TEST(RangeAllocator, RandomStressKeepsRangesDisjoint) {
  // Random allocations and frees; every live range must stay aligned, inside the capacity and
  // disjoint from the others, and freeing everything must restore one free range.
  RangeAllocator r(1 << 20);
  std::mt19937 rng(7);
  struct Live { uint64_t off, size; };
  std::vector<Live> live;
  for (int step = 0; step < 4000; ++step) {
    if (live.empty() || rng() % 3 != 0) {
      const uint64_t size = 1 + rng() % 5000, align = uint64_t(1) << (rng() % 9);
      if (auto o = r.allocate(size, align)) {
        ASSERT_EQ(*o % align, 0u);
        ASSERT_LE(*o + size, r.capacity());
        for (const auto& l : live) ASSERT_TRUE(*o + size <= l.off || l.off + l.size <= *o);
        live.push_back({*o, size});
      }
    } else {
      const size_t i = rng() % live.size();
      r.free(live[i].off, live[i].size);
      live.erase(live.begin() + long(i));
    }
  }
  for (const auto& l : live) r.free(l.off, l.size);
  EXPECT_EQ(r.free_range_count(), 1u);
  EXPECT_EQ(r.used(), 0u);
}

class MemoryAllocatorTest : public test::VulkanTest {};

TEST_F(MemoryAllocatorTest, ManyBuffersShareOneBlock) {
  const size_t blocks_before = ctx->allocator().block_count();
  {
    std::vector<Buffer> buffers;
    for (int i = 0; i < 200; ++i) buffers.emplace_back(*ctx, 4096, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    // 200 x 4 KiB fit one 64 MiB block: one vkAllocateMemory, not 200.
    EXPECT_LE(ctx->allocator().block_count(), blocks_before + 1);
    EXPECT_GE(ctx->allocator().bytes_in_use(), 200u * 4096u);
  }
  EXPECT_EQ(ctx->allocator().bytes_in_use(), 0u);
}

TEST_F(MemoryAllocatorTest, UploadAndDownloadRoundTrip) {
  std::vector<uint32_t> data(10000);
  for (size_t i = 0; i < data.size(); ++i) data[i] = uint32_t(i * 2654435761u);
  Buffer b = Buffer::storage(*ctx, data);
  const auto bytes = b.download();
  ASSERT_EQ(bytes.size(), data.size() * 4);
  EXPECT_EQ(std::memcmp(bytes.data(), data.data(), bytes.size()), 0);
}

TEST_F(MemoryAllocatorTest, LargeRequestGetsItsOwnBlock) {
  Buffer big(*ctx, MemoryAllocator::kBlockSize + 4096, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  Buffer small(*ctx, 256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  EXPECT_GE(ctx->allocator().bytes_in_use(), MemoryAllocator::kBlockSize + 4096 + 256);
}

TEST_F(MemoryAllocatorTest, MoreThanTheDeviceHasIsAnInputError) {
  // What a resolution or a technique parameter too large for the device asks for: the user's
  // input, so exit 2 with what was asked, not an internal error.
  VkMemoryRequirements req{};
  req.size = uint64_t(1) << 62;
  req.alignment = 256;
  req.memoryTypeBits = ~0u;
  const size_t blocks = ctx->allocator().block_count();
  try {
    ctx->allocator().allocate(req, MemoryUsage::Device, true);
    FAIL() << "an allocation of 4 EiB succeeded";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "GPU memory");
    EXPECT_NE(std::string(e.what()).find("a resource of 4398046511104 MiB"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("lower --width/--height"), std::string::npos) << e.what();
  }
  EXPECT_EQ(ctx->allocator().block_count(), blocks);
}

}  // namespace
}  // namespace giq::realtime
