// Wall forces sampled over an experiment: one row per sample, per named wall fx fy fz
// (Simulation::wall_forces) and, when the simulation sums them, the peak and the impulse since the
// previous sample, written as wall_forces.csv like `repose run` does.
#pragma once
#include <ostream>
#include <string>
#include <vector>

#include "engine/simulation.h"

namespace repose {

struct WallForceSeries {
  std::vector<std::string> names;
  std::vector<double> times;
  std::vector<std::vector<WallForce>> rows;
  // When the simulation sums the walls' forces (Simulation::sum_wall_forces): per row each wall's
  // peak and impulse since the previous row.
  std::vector<std::vector<WallImpulse>> impulses;

  void sample(Simulation& sim);
  void write_csv(std::ostream& out) const;
};

}  // namespace repose
