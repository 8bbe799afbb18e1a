// The full state after a run, as bytes in a stable, documented order (docs/state-format.md),
// so that two runs, two thread counts or two backends can be compared with `cmp`.
#pragma once
#include <cstdint>
#include <string>

#include "engine/backend.h"

namespace repose {

// Version 3 adds the rolling springs (a count, then one vec4 per contact); version 2 files
// (no rolling springs) still read.
constexpr char kStateMagic[8] = {'R', 'E', 'P', 'O', 'S', 'E', 'S', '3'};
constexpr char kStateMagicV2[8] = {'R', 'E', 'P', 'O', 'S', 'E', 'S', '2'};

void write_state_file(const std::string& path, const HostState& state, uint64_t step, double time);
// Reads a file written by write_state_file; throws naming the file when it is not one.
HostState read_state_file(const std::string& path, uint64_t* step = nullptr, double* time = nullptr);

}  // namespace repose
