// Creates a backend by name: "vulkan" (device index, -1 = default), "cpu" (threads, 0 = all) or
// "auto" (the fastest on this machine, choose_backend).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "engine/backend.h"
#include "vk/context.h"

namespace repose {

// The backend a run uses when the user names none, and why.
struct BackendChoice {
  std::string backend;  // "vulkan" or "cpu"
  int device = -1;      // Vulkan device index (vulkan only)
  std::string reason;
};

// A hardware GPU through Vulkan when there is one (discrete before integrated), else the cpu
// backend: lavapipe, Vulkan on the CPU, is several times slower than the cpu backend on the same
// cores. It stays the bit-exact reference device on request (--backend vulkan --device N).
BackendChoice choose_backend(const std::vector<vk::DeviceInfo>& devices);
// choose_backend over this machine's Vulkan devices (none when Vulkan itself is missing).
BackendChoice default_backend();
// A user's --backend and --device: "auto" with a device means Vulkan on it, without one
// default_backend(); "vulkan" and "cpu" stay as named.
BackendChoice resolve_backend(const std::string& name, int device);

std::unique_ptr<Backend> make_backend(const std::string& name, int device, unsigned threads,
                                      uint32_t workgroup);

}  // namespace repose
