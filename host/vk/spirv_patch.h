// Edits to a compiled SPIR-V module made when it is loaded, for what only some devices offer.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace repose::vk {

// The module with 32-bit denormals kept (SPV_KHR_float_controls: DenormPreserve 32 on every entry
// point), for devices that offer it (shaderDenormPreserveFloat32): a GPU that flushes denormals
// to zero would otherwise end a decaying spin a few steps before the CPU twin does, which keeps
// them as IEEE says. lavapipe keeps them without being asked (and does not offer the mode).
std::vector<uint32_t> with_denormals_preserved(const uint32_t* words, size_t count);

}  // namespace repose::vk
