#include "engine/bench_bed.h"

#include <cmath>
#include <random>

#include "case/particle_factory.h"
#include "util/math.h"

namespace repose {

CaseSpec bench_bed_case(uint32_t n, uint64_t seed) {
  const double r = 0.005;
  CaseSpec c;
  c.path = "<bench bed>";
  c.name = "bench_bed";
  c.seed = seed;
  c.time.rayleigh_fraction = 0.2;
  c.time.end_time = 1.0;
  c.materials.push_back({"grain", 850.0, 0.0, 1.09e6, 0.32, {}});
  c.materials.push_back({"steel", 7850.0, 0.0, 8.2e10, 0.28, {}});
  c.interactions.push_back({0, 0, 0.42, 0.457, 0.039, {}});
  c.interactions.push_back({0, 1, 0.43, 0.67, 0.0476, {}});

  // Footprint L with a settled height ~L/2 at solid fraction ~0.6.
  double volume = n * 4.0 / 3.0 * kPi * r * r * r / 0.6;
  double width = std::cbrt(2.0 * volume);
  double spacing = 2.2 * r;
  int per_side = std::max(1, int(std::floor((width - 2 * r) / spacing)));
  std::mt19937_64 rng(seed);
  for (uint32_t i = 0; i < n; ++i) {
    int ix = int(i % per_side), iy = int((i / per_side) % per_side), iz = int(i / (per_side * per_side));
    auto jitter = [&] { return (unit_interval(rng()) - 0.5) * 0.1 * r; };
    SphereSpec s;
    s.radius = r;
    s.material = 0;
    s.position = {-width / 2 + r + spacing * (ix + 0.5) + jitter(),
                  -width / 2 + r + spacing * (iy + 0.5) + jitter(), r + spacing * (iz + 0.5)};
    c.spheres.push_back(s);
  }
  double top = r + spacing * (double(n) / (per_side * per_side) + 2);
  WallSpec box;
  box.type = WallSpec::Type::Box;
  box.material = 1;
  box.name = "box";
  box.box_min = {-width / 2, -width / 2, 0.0};
  box.box_max = {width / 2, width / 2, top};
  c.walls.push_back(box);
  return c;
}

}  // namespace repose
