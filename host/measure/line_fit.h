// Ordinary least-squares line y = intercept + slope * x, as the seeds fitted their heap slopes.
#pragma once
#include <cstddef>
#include <vector>

namespace repose {

struct LineFit {
  double slope = 0.0;
  double intercept = 0.0;
  double r_squared = 0.0;  // 1 - SS_res / SS_tot (1 when all y are equal and fitted exactly)
  size_t points = 0;
};

// Centred sums (x and y about their means) keep the fit accurate far from the origin. Throws
// std::invalid_argument for fewer than two points, mismatched sizes, or all x equal.
LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace repose
