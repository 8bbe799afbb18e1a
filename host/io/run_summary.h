// DIR/summary.json of a run: what a user reads first, and what scripts parse.
#pragma once
#include <string>

#include "engine/simulation.h"

namespace repose {

struct RunInfo {
  std::string backend;
  std::string variant;
  double wall_seconds = 0;
  unsigned frames = 0;
  std::vector<WallForce> wall_forces;  // at the end of the run (Simulation::wall_forces)
};

void write_run_summary(const std::string& path, const Simulation& sim, const RunInfo& info);

}  // namespace repose
