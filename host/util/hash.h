// A short content hash for identities (case and plan hashes): FNV-1a 64, as 16 hex digits.
// Not cryptographic: it tells edits apart, it does not resist forgery.
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace repose {

inline std::string fnv1a_hex(std::string_view text) {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a offset basis
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", (unsigned long long)h);
  return hex;
}

}  // namespace repose
