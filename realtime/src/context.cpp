#include "giq/realtime/context.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>

#include "giq/base/error.h"
#include "giq/realtime/allocator.h"
#include "giq/realtime/vk.h"

namespace giq::realtime {

const char* vk_result_name(VkResult r) {
  switch (r) {
#define GIQ_CASE(x) \
  case x: return #x;
    GIQ_CASE(VK_SUCCESS)
    GIQ_CASE(VK_NOT_READY)
    GIQ_CASE(VK_TIMEOUT)
    GIQ_CASE(VK_INCOMPLETE)
    GIQ_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    GIQ_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    GIQ_CASE(VK_ERROR_INITIALIZATION_FAILED)
    GIQ_CASE(VK_ERROR_DEVICE_LOST)
    GIQ_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    GIQ_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    GIQ_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    GIQ_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    GIQ_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    GIQ_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    GIQ_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    GIQ_CASE(VK_ERROR_FRAGMENTED_POOL)
    GIQ_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
#undef GIQ_CASE
    default: return "VkResult(unknown)";
  }
}

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

const char* type_name(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
  }
}

// Lower is preferred: a discrete GPU first, a CPU implementation (lavapipe) last.
int type_rank(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
  }
}

bool has_extension(VkPhysicalDevice pd, const char* name) {
  uint32_t n = 0;
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> ext(n);
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, ext.data());
  for (const auto& e : ext)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

// The queue family that does graphics and compute with timestamps; -1 when none.
int find_queue_family(VkPhysicalDevice pd, uint32_t* timestamp_bits) {
  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
  std::vector<VkQueueFamilyProperties> q(n);
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, q.data());
  for (uint32_t i = 0; i < n; ++i) {
    const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    if ((q[i].queueFlags & need) == need && q[i].timestampValidBits > 0) {
      if (timestamp_bits) *timestamp_bits = q[i].timestampValidBits;
      return int(i);
    }
  }
  return -1;
}

DeviceInfo describe(VkPhysicalDevice pd, uint32_t index) {
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
  vkGetPhysicalDeviceProperties2(pd, &props);
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f13};
  DeviceInfo d;
  d.index = index;
  d.name = props.properties.deviceName;
  d.driver = std::string(driver.driverName) + " " + driver.driverInfo;
  d.type = type_name(props.properties.deviceType);
  d.api_version = props.properties.apiVersion;
  if (VK_API_VERSION_MINOR(d.api_version) < 3 && VK_API_VERSION_MAJOR(d.api_version) == 1) {
    d.unusable_reason = "Vulkan 1.3 required";
    return d;
  }
  vkGetPhysicalDeviceFeatures2(pd, &features);
  if (!f13.dynamicRendering || !f13.synchronization2)
    d.unusable_reason = "dynamicRendering and synchronization2 required";
  else if (!features.features.geometryShader)
    d.unusable_reason = "geometryShader feature required (gl_PrimitiveID in fragment shaders)";
  else if (!has_extension(pd, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME))
    d.unusable_reason = "VK_KHR_push_descriptor required";
  else if (find_queue_family(pd, nullptr) < 0)
    d.unusable_reason = "no graphics+compute queue with timestamps";
  else
    d.usable = true;
  return d;
}

bool layer_available(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  for (const auto& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

VkInstance create_instance(bool validation, const VkDebugUtilsMessengerCreateInfoEXT* messenger) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "giq";
  app.pEngineName = "giq";
  app.apiVersion = VK_API_VERSION_1_3;
  std::vector<const char*> layers, extensions;
  if (validation) {
    if (!layer_available(kValidationLayer))
      throw std::runtime_error(std::string("validation requested but ") + kValidationLayer +
                               " is not installed (Debian: vulkan-validationlayers)");
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ci.pNext = validation ? messenger : nullptr;  // also catches messages from vkCreateInstance
  ci.pApplicationInfo = &app;
  ci.enabledLayerCount = uint32_t(layers.size());
  ci.ppEnabledLayerNames = layers.data();
  ci.enabledExtensionCount = uint32_t(extensions.size());
  ci.ppEnabledExtensionNames = extensions.data();
  VkInstance instance = VK_NULL_HANDLE;
  vk_check(vkCreateInstance(&ci, nullptr, &instance), "vkCreateInstance");
  return instance;
}

std::vector<VkPhysicalDevice> physical_devices(VkInstance instance) {
  uint32_t n = 0;
  vk_check(vkEnumeratePhysicalDevices(instance, &n, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> pds(n);
  vk_check(vkEnumeratePhysicalDevices(instance, &n, pds.data()), "vkEnumeratePhysicalDevices");
  return pds;
}

std::string list_for_message(const std::vector<DeviceInfo>& all) {
  std::string s;
  for (const auto& d : all)
    s += (s.empty() ? "" : ", ") + std::to_string(d.index) + ": " + d.name +
         (d.usable ? "" : " (unusable: " + d.unusable_reason + ")");
  return s.empty() ? "none" : s;
}

}  // namespace

bool ContextOptions::default_validation() {
  if (const char* v = std::getenv("GIQ_VALIDATION")) return std::strcmp(v, "0") != 0;
#ifdef NDEBUG
  return false;
#else
  return true;
#endif
}

std::vector<DeviceInfo> Context::enumerate_devices() {
  VkInstance instance = create_instance(false, nullptr);
  std::vector<DeviceInfo> out;
  const auto pds = physical_devices(instance);
  for (uint32_t i = 0; i < pds.size(); ++i) out.push_back(describe(pds[i], i));
  vkDestroyInstance(instance, nullptr);
  return out;
}

VKAPI_ATTR VkBool32 VKAPI_CALL Context::on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void* self) {
  auto* ctx = static_cast<Context*>(self);
  const char* level = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning";
  std::lock_guard lock(ctx->messages_mutex_);
  ctx->messages_.push_back(std::string(level) + ": " + (data->pMessage ? data->pMessage : ""));
  return VK_FALSE;
}

Context::Context(const ContextOptions& options) : validation_(options.validation) {
  VkDebugUtilsMessengerCreateInfoEXT mci{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  mci.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  mci.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                    VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  mci.pfnUserCallback = &Context::on_message;
  mci.pUserData = this;
  instance_ = create_instance(validation_, &mci);
  try {
    if (validation_) {
      auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
      vk_check(create(instance_, &mci, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
    }

    const auto pds = physical_devices(instance_);
    std::vector<DeviceInfo> all;
    for (uint32_t i = 0; i < pds.size(); ++i) all.push_back(describe(pds[i], i));
    int chosen = -1;
    if (options.device.empty()) {
      for (uint32_t i = 0; i < pds.size(); ++i) {
        if (!all[i].usable) continue;
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(pds[i], &p);
        VkPhysicalDeviceProperties best{};
        if (chosen >= 0) vkGetPhysicalDeviceProperties(pds[chosen], &best);
        if (chosen < 0 || type_rank(p.deviceType) < type_rank(best.deviceType)) chosen = int(i);
      }
      if (chosen < 0) throw InputError("", "--device", "no usable Vulkan device; found " + list_for_message(all));
    } else {
      const bool numeric = std::all_of(options.device.begin(), options.device.end(),
                                       [](unsigned char c) { return std::isdigit(c); });
      for (uint32_t i = 0; i < pds.size() && chosen < 0; ++i) {
        if (numeric ? std::to_string(i) == options.device
                    : lower(all[i].name).find(lower(options.device)) != std::string::npos)
          chosen = int(i);
      }
      if (chosen < 0)
        throw InputError("", "--device", "no Vulkan device matches '" + options.device + "'; expected an index or a name among: " + list_for_message(all));
      if (!all[chosen].usable)
        throw InputError("", "--device", "device '" + all[chosen].name + "' cannot run giq: " + all[chosen].unusable_reason);
    }
    physical_ = pds[chosen];
    info_ = all[chosen];
    vkGetPhysicalDeviceProperties(physical_, &properties_);
    queue_family_ = uint32_t(find_queue_family(physical_, &timestamp_bits_));

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qci.queueFamilyIndex = queue_family_;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    f13.dynamicRendering = VK_TRUE;
    f13.synchronization2 = VK_TRUE;
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
    f12.hostQueryReset = VK_TRUE;  // core in 1.2 and required by it
    // Required by Vulkan 1.3: textures are read through buffer device addresses (SceneGpu),
    // past maxStorageBufferRange (128 MiB on lavapipe).
    f12.bufferDeviceAddress = VK_TRUE;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
    features.features.geometryShader = VK_TRUE;
    const char* extensions[] = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    dci.enabledExtensionCount = 1;
    dci.ppEnabledExtensionNames = extensions;
    vk_check(vkCreateDevice(physical_, &dci, nullptr, &device_), "vkCreateDevice");
    vkGetDeviceQueue(device_, queue_family_, 0, &queue_);
    cmd_push_descriptor_set = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
        vkGetDeviceProcAddr(device_, "vkCmdPushDescriptorSetKHR"));

    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pci.queueFamilyIndex = queue_family_;
    vk_check(vkCreateCommandPool(device_, &pci, nullptr, &command_pool_), "vkCreateCommandPool");
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    vk_check(vkCreateFence(device_, &fci, nullptr, &fence_), "vkCreateFence");
    allocator_ = std::make_unique<MemoryAllocator>(device_, physical_);
  } catch (...) {
    release();
    throw;
  }
}

Context::~Context() { release(); }

void Context::release() {
  if (device_) vkDeviceWaitIdle(device_);
  allocator_.reset();
  if (fence_) vkDestroyFence(device_, fence_, nullptr);
  if (command_pool_) vkDestroyCommandPool(device_, command_pool_, nullptr);
  if (device_) vkDestroyDevice(device_, nullptr);
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
  fence_ = VK_NULL_HANDLE, command_pool_ = VK_NULL_HANDLE, device_ = VK_NULL_HANDLE;
  messenger_ = VK_NULL_HANDLE, instance_ = VK_NULL_HANDLE;
}

std::vector<std::string> Context::validation_messages() const {
  std::lock_guard lock(messages_mutex_);
  return messages_;
}

void Context::clear_validation_messages() {
  std::lock_guard lock(messages_mutex_);
  messages_.clear();
}

void Context::submit_and_wait(const std::function<void(VkCommandBuffer)>& record) {
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = command_pool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  vk_check(vkAllocateCommandBuffers(device_, &ai, &cmd), "vkAllocateCommandBuffers");
  struct Free {
    VkDevice d;
    VkCommandPool p;
    VkCommandBuffer c;
    ~Free() { vkFreeCommandBuffers(d, p, 1, &c); }
  } free_cmd{device_, command_pool_, cmd};
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vk_check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
  record(cmd);
  vk_check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  vk_check(vkQueueSubmit(queue_, 1, &si, fence_), "vkQueueSubmit");
  vk_check(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  vk_check(vkResetFences(device_, 1, &fence_), "vkResetFences");
}

}  // namespace giq::realtime
