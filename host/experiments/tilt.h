// The tilting-plate tests of both seeds: a body rests on a plate that tilts slowly at a constant
// rate from level; the tilt at which the body starts to move down the plate gives
// mu = tan(alpha): sliding for a body that cannot roll (cabbage seed, four bonded cabbages:
// static friction), rolling for a single stalk (cotton seed: rolling friction angle).
#pragma once
#include <vector>

#include "case/case_spec.h"
#include "experiments/run_options.h"
#include "experiments/wall_force_series.h"

namespace repose {

struct TiltSample {
  double time = 0, angle_deg = 0;
  double displacement = 0;  // body centre along the plate, relative to it, since the tilt began, m
};

struct TiltResult {
  double onset_angle_deg = 0;  // alpha
  double tan_alpha = 0;        // mu_s (slide) or the rolling friction coefficient (tilt roll)
  double onset_time = 0;       // s
  double rolled_fraction = 0;  // first body's rotation x rolling radius / displacement: ~1 rolls, ~0 slides
  std::vector<TiltSample> trajectory;
  WallForceSeries wall_forces;
};

// The plate is [experiment] plate (default the first wall: a rectangle or a plane); its motion is
// replaced by the tilt: about tilt_axis through its centre at tilt_rate deg/s after settle_time.
// Onset: the body centre moved onset_distance relative to the plate. Throws std::runtime_error
// naming the case when the body never moves up to max_angle, or at max_time.
TiltResult run_tilt(const CaseSpec& spec, const ExperimentRunOptions& options = {});

}  // namespace repose
