// How close a run's kernels come to their roofs (README, "Memory roofline" and "Compute ceiling"),
// paired in time: the profiled steps run in segments, each followed by its roofs measured again
// (a copy of the buffers' footprint, a copy through DRAM, the contact law alone), so that a
// shared machine's fast and slow spells fall on a kernel and on its roofs alike. A kernel's
// fraction of a roof is taken per segment and reported as the median and range over them.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "engine/kernel_traffic.h"
#include "engine/run_profile.h"

namespace repose {

class Simulation;

// The roofs right after a segment: each copy's bytes per second (read plus write), and the
// contact law alone's seconds per contact (0 where the backend has none: Vulkan, clumps).
struct Roofs {
  double own = 0, dram = 0, law = 0;
};

struct RoofSegment {
  RunProfile profile;
  Roofs roofs;
};

struct RooflineRun {
  size_t own_bytes = 0;  // the footprint the own copy moves (the simulation's buffers)
  std::vector<RoofSegment> segments;
  RunProfile total() const;
};

// `steps` timed steps of `sim` (profiling on) in `segments` parts, each followed by its roofs (on
// the backend's host threads); with segments = 0, one part and no roofs.
RooflineRun profile_against_roofs(Simulation& sim, uint32_t steps, int segments);

// Each kernel's least bytes per step, the bandwidth it reaches and its fractions of the two
// copies; then contact_forces against the law alone and against the larger of that and its
// bytes at the buffers' copy. Lines indented for `repose bench`.
std::string format_roofline(const RooflineRun& run, const Layout& layout, const TrafficCounts& counts);
std::string format_law_ceiling(const RooflineRun& run, const Layout& layout, const TrafficCounts& counts);

}  // namespace repose
