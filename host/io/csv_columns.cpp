#include "io/csv_columns.h"

#include <sstream>

#include "engine/simulation.h"

namespace repose {

std::string wall_force_csv_header(const std::vector<std::string>& wall_names, bool impulses) {
  std::string header = "t_s";
  for (const auto& n : wall_names) header += "," + n + ".fx_N," + n + ".fy_N," + n + ".fz_N";
  if (impulses)
    for (const auto& n : wall_names) header += "," + n + ".peak_N," + n + ".jx_Ns," + n + ".jy_Ns," + n + ".jz_Ns";
  return header;
}

std::string wall_force_csv_row(double t, const std::vector<WallForce>& forces, const std::vector<WallImpulse>& impulses) {
  std::ostringstream row;
  row << t;
  for (const auto& w : forces) row << "," << w.fx << "," << w.fy << "," << w.fz;
  for (const auto& j : impulses) row << "," << j.peak << "," << j.jx << "," << j.jy << "," << j.jz;
  return row.str();
}

}  // namespace repose
