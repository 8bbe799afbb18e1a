// A parameter a fit searches over a range: the baseline's free parameter of an experiment, or a
// model extension's strength. Searches run in the unit interval, linear or logarithmic.
#pragma once
#include <algorithm>
#include <cmath>
#include <string>

namespace repose {

struct FreeParameter {
  std::string name;  // as reported, e.g. "drag_coefficient"
  std::string unit;
  double lo = 0, hi = 1;   // search range
  bool log_scale = false;  // search log(value) (strengths spanning decades)

  // The value's position in the range, 0 at lo and 1 at hi.
  double to_unit(double v) const {
    return log_scale ? std::log(v / lo) / std::log(hi / lo) : (v - lo) / (hi - lo);
  }
  // The value at position u (clamped to the range).
  double from_unit(double u) const {
    u = std::clamp(u, 0.0, 1.0);
    return log_scale ? lo * std::exp(u * std::log(hi / lo)) : lo + u * (hi - lo);
  }
};

}  // namespace repose
