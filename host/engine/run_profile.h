// Where a run's time goes: seconds per kernel (summed over its dispatches), the steps, list
// rebuilds and contacts behind them, and the wall time around them; what the kernels do not
// account for is host work (uploads, downloads, the experiment's own measurements).
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "engine/backend.h"

namespace repose {

struct RunProfile {
  KernelTimes kernels;       // empty unless kernels were timed (Simulation::set_profiling)
  double wall_seconds = 0;
  uint64_t steps = 0;
  uint64_t rebuilds = 0;
  double contact_steps = 0;  // contacts summed over steps (each batch counts its last list)
  uint64_t reorders = 0;       // cell orderings on the host (download, sort, upload) and their time
  double reorder_seconds = 0;
  void add(const RunProfile& other);
  double kernel_seconds() const;
};

// The stage of a step a kernel belongs to: "neighbours" (the list rebuild), "contacts" (forces),
// "particles" (gathers and integration of spheres), "bodies" (clumps), "other".
const char* kernel_stage(const std::string& kernel);
inline constexpr const char* kKernelStages[] = {"neighbours", "contacts", "particles", "bodies", "other"};

// A table with one row per (label, profile): steps, simulated and wall seconds, steps/s,
// rebuilds per 1000 steps, mean contacts, and milliseconds per step in each stage, in reorders and
// on the host otherwise.
std::string format_profiles(const std::vector<std::pair<std::string, RunProfile>>& rows, double dt);

// The kernels of one profile, slowest first: milliseconds per step and share of the kernel time.
std::string format_kernel_times(const RunProfile& p);

}  // namespace repose
