#include "measure/bed_height.h"

#include <algorithm>
#include <limits>

namespace repose {

double uniform_bed_height(const std::vector<Sphere>& spheres, const std::optional<double>& floor_z) {
  double lowest = std::numeric_limits<double>::infinity();
  for (const Sphere& s : spheres) lowest = std::min(lowest, s.centre.z - s.radius);
  double floor = floor_z.value_or(lowest), volume = 0, moment = 0;
  for (const Sphere& s : spheres) {
    double v = s.radius * s.radius * s.radius;
    volume += v;
    moment += v * (s.centre.z - floor);
  }
  return volume > 0 ? 2 * moment / volume : 0.0;
}

}  // namespace repose
