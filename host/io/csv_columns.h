// Column names of the CSV files Repose writes: each name ends with its unit (`t_s`, `height_m`,
// `plate.fz_N`; docs/outputs.md lists every file), so a spreadsheet reader needs no manual.
#pragma once
#include <string>
#include <vector>

namespace repose {

// The header of wall_forces.csv (`repose run` and the experiments): the time, then per named wall
// its force's components, "t_s,plate.fx_N,plate.fy_N,plate.fz_N", and with `impulses` (the walls'
// forces summed every step) its largest force and its impulse since the previous row,
// "plate.peak_N,plate.jx_Ns,plate.jy_Ns,plate.jz_Ns".
std::string wall_force_csv_header(const std::vector<std::string>& wall_names, bool impulses = false);

// One row: the time, each wall's force, and its peak and impulse when given (one per wall).
struct WallForce;
struct WallImpulse;
std::string wall_force_csv_row(double t, const std::vector<WallForce>& forces, const std::vector<WallImpulse>& impulses);

}  // namespace repose
