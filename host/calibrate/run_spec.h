// One simulation of a campaign: which phase asked for it, which design point and replicate,
// the packing seed and the factor values. Its id is derived from the plan alone, so a resumed
// or distributed campaign names every run the same way.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "calibrate/experiment_runner.h"

namespace repose::calibrate {

struct RunSpec {
  std::string id;     // "design-007-r0", "verify-r2", "loop-004", "pilot-1-r3", "loop-004@cylinder"
  std::string phase;  // design, verify, loop, pilot
  int point = 0;      // design point (standard order) or loop iteration
  int replicate = 0;  // seed = base_seed + replicate
  std::uint64_t seed = 0;
  std::vector<double> x;  // actual factor values, in plan order
  int rig = 0;            // the plan's rig it runs on (ids on rig r > 0 end in "@NAME")
};

// A finished run as stored: the spec, its responses, and where and how long it ran.
struct RunRecord {
  RunSpec spec;
  Responses responses;
  double wall_s = 0;
  std::string host;
  int rank = 0;
};

}  // namespace repose::calibrate
