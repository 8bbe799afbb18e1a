// Process-wide switches (default on) between each group of the CPU twin's SIMD-lane kernels and
// the scalar kernels they mirror, for measuring one against the other (`repose bench
// --scalar-contacts`, `--scalar-kick`, `--scalar-bodies`, `--scalar-neighbours`): the bytes are the
// same either way.
#pragma once

namespace repose::gpu {

enum class LaneKernels {
  Contacts,  // contact_forces (contact_lanes.h)
  Kick,      // kick_drift and gather_kick's kick (kick_lanes.h)
  Bodies,    // body_place and body_gather_kick (body_lanes.h)
  Neighbours,  // contact_count's walk and contact_fill (walk_lanes.h), the transposed rows filled in order (cpu_kernels.cpp)
};

void set_lanes(LaneKernels which, bool on);
bool lanes_enabled(LaneKernels which);

}  // namespace repose::gpu
