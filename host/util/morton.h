// Morton (Z-order) codes of grid cells: cells close in space get close codes, so sorting by the
// code puts neighbours near each other in memory (large particle fills).
#pragma once
#include <cstdint>

namespace repose {

// Interleaves the low 21 bits of x, y and z.
inline uint64_t morton_code(uint64_t x, uint64_t y, uint64_t z) {
  auto spread = [](uint64_t v) {
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffull;
    v = (v | v << 16) & 0x1f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
  };
  return spread(x) | spread(y) << 1 | spread(z) << 2;
}

}  // namespace repose
