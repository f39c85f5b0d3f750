#pragma once
// A headless Vulkan 1.3 context: instance, one physical device chosen by policy or by the
// user, one queue that does graphics, compute and transfer, a device-memory sub-allocator and
// the validation layer's messages. No window, no swapchain: everything renders off-screen.

#include <vulkan/vulkan.h>

#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace giq::realtime {

class MemoryAllocator;

struct DeviceInfo {
  uint32_t index = 0;        // position in vkEnumeratePhysicalDevices
  std::string name;          // VkPhysicalDeviceProperties::deviceName
  std::string driver;        // driverName + driverInfo (VkPhysicalDeviceDriverProperties)
  std::string type;          // "discrete", "integrated", "virtual", "cpu", "other"
  uint32_t api_version = 0;  // VK_MAKE_API_VERSION
  bool usable = false;       // Vulkan 1.3 with the features giq needs
  std::string unusable_reason;
};

struct ContextOptions {
  // "" = automatic (first usable discrete GPU, else integrated, else virtual, else a CPU
  // implementation such as lavapipe); else a device index or a case-insensitive substring of
  // the device name.
  std::string device;
  // Enable VK_LAYER_KHRONOS_validation and record every warning and error it reports.
  // Default: on in debug builds and when GIQ_VALIDATION=1, off otherwise.
  bool validation = default_validation();
  static bool default_validation();
};

class Context {
 public:
  explicit Context(const ContextOptions& options = {});
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  // Every device the loader reports, with why it is or is not usable.
  static std::vector<DeviceInfo> enumerate_devices();

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physical_device() const { return physical_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queue_family() const { return queue_family_; }
  const DeviceInfo& info() const { return info_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  MemoryAllocator& allocator() { return *allocator_; }

  // Nanoseconds per timestamp tick, and the valid bits of the queue's timestamps.
  double timestamp_period_ns() const { return properties_.limits.timestampPeriod; }
  uint32_t timestamp_valid_bits() const { return timestamp_bits_; }

  bool validation_enabled() const { return validation_; }
  // Messages (warnings and errors) the validation layer reported so far; tests require none.
  std::vector<std::string> validation_messages() const;
  void clear_validation_messages();

  // Records commands into a fresh primary command buffer, submits it and waits.
  void submit_and_wait(const std::function<void(VkCommandBuffer)>& record);

  // VK_KHR_push_descriptor: descriptors are pushed per dispatch, so no pools to manage.
  PFN_vkCmdPushDescriptorSetKHR cmd_push_descriptor_set = nullptr;

 private:
  void release();
  static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT types,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void* self);

  bool validation_ = false;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queue_family_ = 0;
  uint32_t timestamp_bits_ = 0;
  VkPhysicalDeviceProperties properties_{};
  DeviceInfo info_;
  VkCommandPool command_pool_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  std::unique_ptr<MemoryAllocator> allocator_;
  mutable std::mutex messages_mutex_;
  std::vector<std::string> messages_;
};

}  // namespace giq::realtime
