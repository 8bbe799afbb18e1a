// The environment's test and tuning settings (REPOSE_MAX_GROUPS_X, REPOSE_SCAN_BLOCKS_FROM,
// REPOSE_STAGING): whole numbers read once where they are used.
#pragma once
#include <cstdint>

namespace repose {

// The whole number 1 ... `most` in environment variable `name`, or `fallback` when it is unset or
// empty; anything else throws std::invalid_argument naming the variable and the range.
uint64_t env_whole_number(const char* name, uint64_t fallback, uint64_t most);

}  // namespace repose
