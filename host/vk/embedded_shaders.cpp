#include "vk/embedded_shaders.h"

#include <stdexcept>

namespace repose::vk {

#include "shader_table.inc"

const EmbeddedShader& embedded_shader(const std::string& name) {
  for (const auto& s : kEmbeddedShaders)
    if (name == s.name) return s;
  throw std::runtime_error("no embedded shader named '" + name + "'");
}

}  // namespace repose::vk
