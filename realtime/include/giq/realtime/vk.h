#pragma once
// Vulkan error checking shared by the real-time module. A failing Vulkan call is a bug or an
// exhausted device, never bad user input, so it throws std::runtime_error (CLI exit 3) naming
// the call and the VkResult.

#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>

namespace giq::realtime {

const char* vk_result_name(VkResult r);

inline void vk_check(VkResult r, const char* what) {
  if (r != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed: " + vk_result_name(r));
}

}  // namespace giq::realtime
