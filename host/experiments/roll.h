// The inclined rolling test of the cabbage seed: the body is released at rest on a plate inclined
// at beta, its contact point a slope distance S above the foot, rolls down and onto a horizontal
// plate, and stops after a distance L there; mu_r = S sin(beta) / (S cos(beta) + L) (seed Eq. 4).
#pragma once
#include <vector>

#include "case/case_spec.h"
#include "experiments/run_options.h"
#include "experiments/wall_force_series.h"

namespace repose {

struct RollSample {
  double time = 0;
  double x = 0;      // body centre along the rolling direction, from the foot of the incline, m
  double speed = 0;  // m/s
};

struct RollResult {
  double incline_deg = 0, slope_distance = 0;
  double rolling_distance = 0;  // L, m, from the foot of the incline to where the body stopped
  double mu_r = 0;              // the seed's formula
  double stop_time = 0;
  double speed_at_foot = 0;     // m/s when the centre passed the foot
  bool stopped = true;          // false: still rolling at max_time (only when not required)
  std::vector<RollSample> trajectory;
  WallForceSeries wall_forces;
};

// The case's particles are the body and its first [[wall]] gives the plates' material; the rig
// (an incline rectangle and a floor plane meeting at x = 0, rolling towards +x, z up) replaces
// the case's walls. Throws std::runtime_error naming the case when the body does not stop on
// the floor by max_time, unless `require_stop` is false: then L is where it got to by then.
RollResult run_roll(const CaseSpec& spec, const ExperimentRunOptions& options = {}, bool require_stop = true);

}  // namespace repose
