#include "experiments/replicates.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "case/body_pose.h"
#include "case/particle_factory.h"

namespace repose {

std::pair<double, double> mean_sd(const std::vector<double>& x) {
  double mean = 0, var = 0;
  for (double v : x) mean += v / double(x.size());
  for (double v : x) var += (v - mean) * (v - mean) / double(std::max<size_t>(1, x.size() - 1));
  return {mean, std::sqrt(var)};
}

void random_body_orientation(CaseSpec& spec, uint64_t seed) {
  auto body = std::find_if(spec.bodies.begin(), spec.bodies.end(), [](const BodySpec& b) { return !b.fixed; });
  if (body == spec.bodies.end()) return;
  std::mt19937_64 engine(seed);
  body->orientation = random_orientation([&engine] { return unit_interval(engine()); });
}

}  // namespace repose
