#include "io/csv_columns.h"

namespace repose {

std::string wall_force_csv_header(const std::vector<std::string>& wall_names) {
  std::string header = "t_s";
  for (const auto& n : wall_names) header += "," + n + ".fx_N," + n + ".fy_N," + n + ".fz_N";
  return header;
}

}  // namespace repose
