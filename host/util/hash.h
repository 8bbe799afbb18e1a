// FNV-1a 64: the content hash of identities (case and plan hashes, as 16 hex digits) and the
// checksum of version 5 state files (docs/state-format.md; version 6 takes XXH3-64, which is
// faster on files of hundreds of MB: io/state_file.cpp). Not cryptographic: it tells edits and damage
// apart (any one changed byte changes it), it does not resist forgery.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace repose {

// The hash of bytes fed in pieces: the same value as of their concatenation.
class Fnv1a {
 public:
  void add(const void* data, std::size_t bytes) {
    const unsigned char* p = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < bytes; ++k) {
      h_ ^= p[k];
      h_ *= 1099511628211ull;  // FNV prime
    }
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 1469598103934665603ull;  // FNV-1a offset basis
};

inline std::string hex16(std::uint64_t v) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", (unsigned long long)v);
  return hex;
}

inline std::string fnv1a_hex(std::string_view text) {
  Fnv1a h;
  h.add(text.data(), text.size());
  return hex16(h.value());
}

}  // namespace repose
