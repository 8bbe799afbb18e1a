// Where a run's time goes: seconds per kernel (summed over its dispatches), the steps, list
// rebuilds and contacts behind them, and the wall time around them; what the kernels do not
// account for is host work (uploads, downloads, the experiment's own measurements).
#pragma once
#include <chrono>
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
  // Of that time: the state down, put in its new slots on the host, and up again (with the constants).
  struct ReorderParts {
    double download = 0, order = 0, upload = 0;
  } reorder_parts;
  // What a timed run can name of the host's share (the wall time no kernel nor reorder took): the
  // backend's batches (their kernels included) and their device overheads; the transfers around
  // them (walls up, control words and the state down).
  double batch_seconds = 0;
  DeviceOverheads device;
  double transfer_seconds = 0;
  void add(const RunProfile& other);
  void add(const ExecuteTimes& batch);
  double kernel_seconds() const;
};

// Adds the seconds of its life to *into (nothing when into is null: a run not timed).
class ProfileClock {
 public:
  explicit ProfileClock(double* into) : into_(into), start_(std::chrono::steady_clock::now()) {}
  ~ProfileClock() {
    if (into_) *into_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  ProfileClock(const ProfileClock&) = delete;
  ProfileClock& operator=(const ProfileClock&) = delete;

 private:
  double* into_;
  std::chrono::steady_clock::time_point start_;
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

// The host's share of one timed profile, per step, in the parts it can name (RunProfile); empty
// when the kernels were not timed.
std::string format_host_times(const RunProfile& p);

}  // namespace repose
