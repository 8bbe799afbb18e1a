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
};

void write_run_summary(const std::string& path, Simulation& sim, const RunInfo& info);

}  // namespace repose
