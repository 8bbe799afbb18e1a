// VK_CHECK: a failed Vulkan call throws with the expression, the result's name and file:line.
#pragma once
#include <stdexcept>
#include <string>
#include <vulkan/vulkan.h>

namespace repose::vk {

const char* result_name(VkResult r);

struct VulkanError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] void throw_vk_error(const char* expr, VkResult r, const char* file, int line);

}  // namespace repose::vk

#define VK_CHECK(expr)                                                              \
  do {                                                                              \
    VkResult vk_check_result_ = (expr);                                             \
    if (vk_check_result_ != VK_SUCCESS)                                             \
      ::repose::vk::throw_vk_error(#expr, vk_check_result_, __FILE__, __LINE__);    \
  } while (0)
