// Creates a backend by name: "vulkan" (device index, -1 = default) or "cpu" (threads, 0 = all).
#pragma once
#include <memory>
#include <string>

#include "engine/backend.h"

namespace repose {

std::unique_ptr<Backend> make_backend(const std::string& name, int device, unsigned threads,
                                      uint32_t workgroup);

}  // namespace repose
