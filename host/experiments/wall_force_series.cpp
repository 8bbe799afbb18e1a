#include "experiments/wall_force_series.h"

#include "io/csv_columns.h"

namespace repose {

void WallForceSeries::sample(Simulation& sim) {
  if (sim.model().walls.empty()) return;
  if (names.empty()) names = sim.model().wall_group_names();
  times.push_back(sim.time());
  rows.push_back(sim.wall_forces());
}

void WallForceSeries::write_csv(std::ostream& out) const {
  out << wall_force_csv_header(names) << "\n";
  for (size_t k = 0; k < rows.size(); ++k) {
    out << times[k];
    for (const auto& f : rows[k]) out << "," << f.fx << "," << f.fy << "," << f.fz;
    out << "\n";
  }
}

}  // namespace repose
