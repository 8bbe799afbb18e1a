// The walls' forces summed every step (Simulation::sum_wall_forces): the impulse a plate takes
// from a bouncing sphere balances the sphere's momentum change and its weight's impulse; the peak
// is the largest force of any step, as stepping one step at a time finds it; the sums are the same
// bytes on the cpu backend, with any thread count, and on lavapipe.
#include <catch2/catch.hpp>

#include <cmath>

#include "engine_test_support.h"

using namespace repose;
using namespace repose::test;

namespace {

// A 10 mm sphere dropped from 5 cm onto a plate, bouncing for 0.2 s.
CaseSpec bounce() {
  CaseBuilder b;
  int grain = b.material(1000, 5e6, 0.3), steel = b.material(7800, 8e10, 0.3);
  b.interaction(grain, steel, 0.5, 0.4, 0.0);
  b.spec.gravity = {0, 0, -9.81};
  b.spec.time.rayleigh_fraction = 0.2;
  b.sphere({0, 0, 0.06}, 0.01, grain);
  b.plane({0, 0, 0}, {0, 0, 1}, steel);
  return b.spec;
}

std::vector<WallImpulse> summed(const std::string& backend, unsigned threads, uint64_t steps) {
  Model model = build_model(bounce());
  Simulation sim(model, make_backend(backend, -1, threads, gpu::kDefaultWorkgroup), KernelVariant::fastest_for(backend, model), 100);
  sim.sum_wall_forces();
  sim.advance(steps);
  return sim.take_wall_impulses();
}

}  // namespace

TEST_CASE("a plate's impulse balances the bouncing sphere's momentum; its peak is the largest step's force",
          "[engine][walls]") {
  Model model = build_model(bounce());
  const uint64_t steps = uint64_t(0.2 / model.dt);
  Simulation sim(model, make_backend("cpu", -1, 1, gpu::kDefaultWorkgroup), {}, 100);
  sim.sum_wall_forces();
  sim.advance(steps);
  std::vector<WallImpulse> j = sim.take_wall_impulses();
  REQUIRE(j.size() == 1);
  // On the sphere: m (v_end - 0) = -m g T + J_sphere, and the plate takes -J_sphere.
  double m = 1.0 / sim.state().vel[0].w, T = double(steps) * model.dt, v_end = sim.state().vel[0].z;
  double j_sphere = m * v_end + m * 9.81 * T;
  CHECK(j_sphere > 0.5 * m * std::sqrt(2 * 9.81 * 0.05));  // it did hit the plate
  // Float forces summed per batch, then in double: 1e-5 of the impulse.
  CHECK(-j[0].jz == Approx(j_sphere).epsilon(1e-5));
  CHECK(std::abs(j[0].jx) < 1e-9);
  // The same steps one at a time: the largest |F| of any step, the sum of F dt.
  Simulation stepwise(model, make_backend("cpu", -1, 1, gpu::kDefaultWorkgroup), {}, 1);
  double peak = 0, jz = 0;
  for (uint64_t k = 0; k < steps; ++k) {
    stepwise.advance(1);
    WallForce f = stepwise.wall_forces()[0];
    peak = std::max(peak, std::sqrt(f.fx * f.fx + f.fy * f.fy + f.fz * f.fz));
    jz += f.fz * model.dt;
  }
  CHECK(j[0].peak == Approx(peak).epsilon(1e-6));  // |F| from its float square, rounded once
  CHECK(j[0].jz == Approx(jz).epsilon(1e-5));
  // A second reading starts anew: nothing since.
  CHECK(sim.take_wall_impulses()[0].jz == 0);
}

TEST_CASE("wall sums are the same bytes on 1 and 2 cpu threads and on lavapipe", "[engine][walls][vulkan]") {
  Model model = build_model(bounce());
  const uint64_t steps = uint64_t(0.05 / model.dt);
  auto a = summed("cpu", 1, steps), b = summed("cpu", 2, steps), c = summed("vulkan", 0, steps);
  for (const auto* other : {&b, &c}) {
    REQUIRE(other->size() == a.size());
    CHECK((*other)[0].jz == a[0].jz);
    CHECK((*other)[0].peak == a[0].peak);
  }
}
