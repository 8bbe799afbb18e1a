#include "experiments/wall_force_series.h"

#include "io/csv_columns.h"

namespace repose {

void WallForceSeries::sample(Simulation& sim) {
  if (sim.model().walls.empty()) return;
  if (names.empty()) names = sim.model().wall_group_names();
  times.push_back(sim.time());
  rows.push_back(sim.wall_forces());
  if (sim.sums_wall_forces()) impulses.push_back(sim.take_wall_impulses());
}

void WallForceSeries::write_csv(std::ostream& out) const {
  out << wall_force_csv_header(names, !impulses.empty()) << "\n";
  for (size_t k = 0; k < rows.size(); ++k)
    out << wall_force_csv_row(times[k], rows[k], impulses.empty() ? std::vector<WallImpulse>{} : impulses[k]) << "\n";
}

}  // namespace repose
