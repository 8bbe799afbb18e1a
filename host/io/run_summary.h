// DIR/summary.json of a run: what a user reads first, and what scripts parse.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "engine/simulation.h"

namespace repose {

struct RunInfo {
  std::string backend;
  std::string variant;
  double wall_seconds = 0;
  unsigned frames = 0;
  std::vector<WallForce> wall_forces;  // at the end of the run (Simulation::wall_forces)
  std::string status = "finished";     // "running", "finished", "interrupted by SIGINT", "failed: REASON"
  struct {
    std::string file;  // the state file a restarted run continued from ("" for a new run)
    uint64_t step = 0;
  } restart;
  nlohmann::ordered_json provenance;   // io/provenance.h
};

void write_run_summary(const std::string& path, const Simulation& sim, const RunInfo& info);

}  // namespace repose
