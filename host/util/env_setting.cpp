#include "util/env_setting.h"

#include <cctype>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace repose {

uint64_t env_whole_number(const char* name, uint64_t fallback, uint64_t most) {
  const char* text = std::getenv(name);
  if (!text || !*text) return fallback;
  char* end = nullptr;
  unsigned long long v = std::strtoull(text, &end, 10);
  if (*end || !std::isdigit(static_cast<unsigned char>(*text)) || v == 0 || v > most)
    throw std::invalid_argument(std::string(name) + " = '" + text + "': give 1 ... " + std::to_string(most));
  return v;
}

}  // namespace repose
