// The free-fall collision test of both seeds: a body released at rest with its lowest point H
// above a plate; a simulated high-speed camera tracks the lowest point, the rebound height h is
// the highest point seen after the first impact, and e = sqrt(h/H) (cabbage seed Eq. 1).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "case/case_spec.h"
#include "engine/step_program.h"
#include "experiments/wall_force_series.h"

namespace repose {

struct DropOptions {
  std::string backend = "cpu";
  int device = -1;
  unsigned threads = 1;
  bool random_orientation = true;  // a clump falls at a random orientation drawn from the seed
};

struct DropResult {
  double drop_height = 0;           // H, m
  double rebound_height = 0;        // h seen by the camera (parabola through the top frames), m
  double rebound_height_exact = 0;  // apex of the free flight after lift-off, m
  double restitution = 0;           // sqrt(h/H)
  double impact_speed = 0;          // m/s, normal to the plate, just before contact
  double contact_time = 0;          // s, first impact
  std::vector<std::pair<double, double>> trajectory;  // (t, height of the lowest point)
  WallForceSeries wall_forces;                         // the plate's force at every camera frame
};

// The case's one sphere or one clump is the body (a clump at a random orientation from
// simulation.seed unless options say otherwise), its first plane wall the plate; [experiment]
// drop_height, camera_fps and max_time apply. Throws std::runtime_error naming the case when
// the case is not a drop test or the body never rebounds.
DropResult run_drop(const CaseSpec& spec, const DropOptions& options = {});

}  // namespace repose
