#include "engine/backend_factory.h"

#include <stdexcept>
#include <thread>

#include "engine/cpu_backend.h"
#include "engine/vulkan_backend.h"

namespace repose {

BackendChoice choose_backend(const std::vector<vk::DeviceInfo>& devices) {
  for (const char* type : {"discrete-gpu", "integrated-gpu"})
    for (const auto& d : devices)
      if (d.type == type)
        return {"vulkan", int(d.index), std::string("hardware GPU: ") + d.name + " (" + type + ")"};
  std::string reason = "no hardware GPU";
  for (const auto& d : devices)
    if (d.type == "cpu")
      reason += "; " + d.name + " [" + std::to_string(d.index) +
                "] runs Vulkan on the CPU, slower than the cpu backend (--backend vulkan --device " +
                std::to_string(d.index) + " uses it: the bit-exact reference)";
  return {"cpu", -1, reason};
}

BackendChoice default_backend() {
  std::vector<vk::DeviceInfo> devices;
  try {
    devices = vk::Context::list_devices();
  } catch (const std::exception&) {
    // No Vulkan loader or driver: the cpu backend needs neither.
  }
  return choose_backend(devices);
}

BackendChoice resolve_backend(const std::string& name, int device) {
  if (name != "auto") return {name, device, "as named"};
  if (device >= 0) return {"vulkan", device, "a Vulkan device was named"};
  return default_backend();
}

std::unique_ptr<Backend> make_backend(const std::string& name, int device, unsigned threads,
                                      uint32_t workgroup) {
  if (name == "auto") {
    BackendChoice c = resolve_backend(name, device);
    return make_backend(c.backend, c.device, threads, workgroup);
  }
  if (name == "vulkan") return std::make_unique<VulkanBackend>(device, workgroup);
  if (name == "cpu") {
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    return std::make_unique<CpuBackend>(threads);
  }
  throw std::invalid_argument("unknown backend '" + name + "' (auto, vulkan or cpu)");
}

}  // namespace repose
