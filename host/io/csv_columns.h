// Column names of the CSV files Repose writes: each name ends with its unit (`t_s`, `height_m`,
// `plate.fz_N`; docs/outputs.md lists every file), so a spreadsheet reader needs no manual.
#pragma once
#include <string>
#include <vector>

namespace repose {

// The header of wall_forces.csv (`repose run` and the experiments): the time, then per named wall
// its force's components, "t_s,plate.fx_N,plate.fy_N,plate.fz_N".
std::string wall_force_csv_header(const std::vector<std::string>& wall_names);

}  // namespace repose
