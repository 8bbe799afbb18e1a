#include "engine/backend_factory.h"

#include <stdexcept>
#include <thread>

#include "engine/cpu_backend.h"
#include "engine/vulkan_backend.h"

namespace repose {

std::unique_ptr<Backend> make_backend(const std::string& name, int device, unsigned threads,
                                      uint32_t workgroup) {
  if (name == "vulkan") return std::make_unique<VulkanBackend>(device, workgroup);
  if (name == "cpu") {
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    return std::make_unique<CpuBackend>(threads);
  }
  throw std::invalid_argument("unknown backend '" + name + "' (vulkan or cpu)");
}

}  // namespace repose
