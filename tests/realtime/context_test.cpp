#include <gtest/gtest.h>

#include "giq/base/error.h"
#include "giq/realtime/context.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

TEST(Context, EnumeratesAUsableDevice) {
  const auto devices = Context::enumerate_devices();
  ASSERT_FALSE(devices.empty());
  bool usable = false;
  for (const auto& d : devices) usable |= d.usable;
  EXPECT_TRUE(usable);
}

TEST(Context, UnknownDeviceIsAnInputError) {
  ContextOptions o;
  o.validation = false;
  o.device = "no-such-gpu-name";
  EXPECT_THROW(Context c(o), InputError);
  o.device = "99";
  EXPECT_THROW(Context c(o), InputError);
}

TEST(Context, ChoosesByIndexAndRecordsNameAndDriver) {
  ContextOptions o;
  o.validation = false;
  o.device = "0";
  const auto devices = Context::enumerate_devices();
  if (!devices[0].usable) GTEST_SKIP() << "device 0 is not usable: " << devices[0].unusable_reason;
  Context c(o);
  EXPECT_EQ(c.info().name, devices[0].name);
  EXPECT_FALSE(c.info().driver.empty());
}

class ValidationTest : public test::VulkanTest {};

TEST_F(ValidationTest, MessengerRecordsMisuse) {
  // A deliberate error (a buffer of size 0 is invalid usage) must reach the recorded messages,
  // or the zero-message checks of every other test would prove nothing.
  VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  ci.size = 0;
  ci.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  VkBuffer b = VK_NULL_HANDLE;
  vkCreateBuffer(ctx->device(), &ci, nullptr, &b);
  if (b) vkDestroyBuffer(ctx->device(), b, nullptr);
  EXPECT_FALSE(ctx->validation_messages().empty());
  ctx->clear_validation_messages();
}

}  // namespace
}  // namespace giq::realtime
