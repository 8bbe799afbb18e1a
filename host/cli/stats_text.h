// A number as the statistics verbs print it (verbs_stats.cpp, verbs_optimize.cpp).
#pragma once
#include <cmath>
#include <string>

#include "util/number_text.h"

namespace repose::cli {

// format_g, with round-off about zero printed as 0.
inline std::string num(double v, int digits = 6) {
  if (std::fabs(v) < 1e-12) v = 0;  // coded centres computed as (x - c) / h come out as +-3e-15
  return format_g(v, digits);
}

}  // namespace repose::cli
