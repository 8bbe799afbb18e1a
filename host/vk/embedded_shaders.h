// The SPIR-V of every shaders/*.comp, compiled and validated at build time and embedded.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace repose::vk {

struct EmbeddedShader {
  const char* name;
  const uint32_t* words;
  size_t bytes;
};

// Throws if no shader of that name was built.
const EmbeddedShader& embedded_shader(const std::string& name);

}  // namespace repose::vk
