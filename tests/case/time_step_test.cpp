// The Rayleigh time against a hand computation, and how dt is resolved from it.
#include <catch2/catch.hpp>

#include <cmath>

#include "case/case_error.h"
#include "case/time_step.h"

using namespace repose;

namespace {

CaseSpec two_spheres() {
  CaseSpec spec;
  Material grain{"grain", 850, 2 * 1.09e6 * 1.32, 1.09e6, 0.32, {}};
  Material steel{"steel", 7850, 2 * 8.2e10 * 1.28, 8.2e10, 0.28, {}};
  spec.materials = {grain, steel};
  SphereSpec big, small;
  big.radius = 0.08;
  small.radius = 0.005;
  spec.spheres = {big, small};
  return spec;
}

}  // namespace

TEST_CASE("Rayleigh time matches a hand computation") {
  // pi * 0.005 * sqrt(850 / 1.09e6) / (0.1631 * 0.32 + 0.8766)
  //   = 0.01570796 * 0.02792548 / 0.928792 = 4.722779e-4 s
  CaseSpec spec = two_spheres();
  CHECK(rayleigh_time(spec) == Approx(4.722779015542139e-4).epsilon(1e-12));
  CHECK(rayleigh_time(0.08, spec.materials[0]) == Approx(7.556446424867422e-3).epsilon(1e-12));
  RayleighLimit limit = rayleigh_limit(spec);
  CHECK(limit.sphere == 1);
  // Steel spheres of the same size are much stiffer for their density: a shorter time.
  spec.spheres[0].material = 1;
  spec.spheres[0].radius = 0.005;
  CHECK(rayleigh_limit(spec).sphere == 0);
}

TEST_CASE("dt resolves from seconds or from a fraction of the Rayleigh time") {
  CaseSpec spec = two_spheres();
  spec.time.rayleigh_fraction = 0.2;
  CHECK(resolve_dt(spec) == Approx(0.2 * 4.722779015542139e-4).epsilon(1e-12));
  spec.time.rayleigh_fraction.reset();
  spec.time.dt = 1e-6;
  CHECK(resolve_dt(spec) == 1e-6);
  spec.time.rayleigh_fraction = 0.2;
  CHECK_THROWS_AS(resolve_dt(spec), CaseError);
  spec.spheres.clear();
  spec.time.dt.reset();
  CHECK(std::isinf(rayleigh_time(spec)));
  CHECK_THROWS_AS(resolve_dt(spec), CaseError);
}
