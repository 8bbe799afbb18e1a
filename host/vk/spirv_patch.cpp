#include "vk/spirv_patch.h"

#include <cstring>
#include <stdexcept>

namespace repose::vk {

namespace {

// Opcodes and operands of the SPIR-V specification (section 3).
constexpr uint32_t kOpExtension = 10, kOpExtInstImport = 11, kOpMemoryModel = 14, kOpEntryPoint = 15,
                   kOpCapability = 17;
constexpr uint32_t kOpExecutionMode = 16, kModeDenormPreserve = 4459, kCapabilityDenormPreserve = 4464;
constexpr size_t kHeaderWords = 5;

uint32_t opcode(uint32_t word) { return word & 0xFFFFu; }
uint32_t length(uint32_t word) { return word >> 16; }

std::vector<uint32_t> literal_string(const char* text) {
  std::vector<uint32_t> words((std::strlen(text) + 4) / 4, 0u);  // nul-terminated, padded to words
  std::memcpy(words.data(), text, std::strlen(text));
  return words;
}

}  // namespace

std::vector<uint32_t> with_denormals_preserved(const uint32_t* words, size_t count) {
  if (count < kHeaderWords || words[0] != 0x07230203u) throw std::runtime_error("not a SPIR-V module");
  std::vector<uint32_t> out(words, words + kHeaderWords);
  bool preamble_added = false;
  for (size_t at = kHeaderWords; at < count;) {
    uint32_t op = opcode(words[at]), n = length(words[at]);
    if (n == 0 || at + n > count) throw std::runtime_error("malformed SPIR-V module");
    // The capability and the extension go where capabilities end; the mode after the entry point.
    if (!preamble_added && op != kOpCapability) {
      if (op != kOpExtension && op != kOpExtInstImport && op != kOpMemoryModel)
        throw std::runtime_error("unexpected SPIR-V layout");
      out.insert(out.end(), {(2u << 16) | kOpCapability, kCapabilityDenormPreserve});
      std::vector<uint32_t> name = literal_string("SPV_KHR_float_controls");
      out.push_back(uint32_t((1 + name.size()) << 16) | kOpExtension);
      out.insert(out.end(), name.begin(), name.end());
      preamble_added = true;
    }
    out.insert(out.end(), words + at, words + at + n);
    if (op == kOpEntryPoint) out.insert(out.end(), {(4u << 16) | kOpExecutionMode, words[at + 2], kModeDenormPreserve, 32u});
    at += n;
  }
  return out;
}

}  // namespace repose::vk
