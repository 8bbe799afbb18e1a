// The LIGGGHTS 3.8 reference measured on these machines (docs/engineering.md, contact law):
// a 160 mm cabbage-like sphere dropped on steel with e = 0.43.
#include <catch2/catch.hpp>

#include "engine_test_support.h"

using namespace repose;
using namespace repose::test;

namespace {

const double kR = 0.08;

CaseBuilder drop_case(double gravity, Vec3d start, Vec3d velocity) {
  CaseBuilder b;
  int cabbage = b.material(850, 1.09e6, 0.32);
  int steel = b.material(7850, 8.2e10, 0.28);
  b.interaction(cabbage, cabbage, 0.42, 0.457, 0.039);
  b.interaction(cabbage, steel, 0.43, 0.457, 0.039);
  b.spec.gravity = {0, 0, -gravity};
  b.spec.time.dt = 1e-5;  // ~1400 steps per contact: converged to 1e-4 in the ratio
  b.sphere(start, kR, cabbage, velocity);
  b.plane({0, 0, 0}, {0, 0, 1}, steel);
  return b;
}

// Runs until the sphere has left the plane moving up; returns its state then.
gpu::vec4 after_bounce(Simulation& sim, gpu::vec4* pos) {
  bool touched = false;
  for (int batch = 0; batch < 2000; ++batch) {
    sim.advance(50);
    const auto& p = sim.state().pos[0];
    const auto& v = sim.state().vel[0];
    if (p.z < kR) touched = true;
    if (touched && p.z > kR && v.z > 0) {
      *pos = p;
      return v;
    }
  }
  FAIL("the sphere never bounced");
  return {};
}

}  // namespace

TEST_CASE("LIGGGHTS drop reference without gravity: v_out/v_in = 0.4299 (0.002)", "[engine][liggghts]") {
  double v_in = std::sqrt(2 * 9.81 * 0.5);
  CaseBuilder b = drop_case(0.0, {0, 0, kR + 0.0005}, {0, 0, -v_in});
  auto sim = simulate(b.spec, "cpu", 1, {}, 50);
  gpu::vec4 pos;
  gpu::vec4 v = after_bounce(*sim, &pos);
  INFO("v_out/v_in = " << v.z / v_in);
  CHECK(std::abs(v.z / v_in - 0.4299) < 0.002);
}

TEST_CASE("LIGGGHTS drop reference with gravity: sqrt(h/H) from 0.3 to 0.5 m (0.002)", "[engine][liggghts]") {
  const double heights[] = {0.30, 0.35, 0.40, 0.45, 0.50};
  const double liggghts[] = {0.4145, 0.4159, 0.4170, 0.4179, 0.4186};
  for (int k = 0; k < 5; ++k) {
    double H = heights[k];
    CaseBuilder b = drop_case(9.81, {0, 0, kR + H}, {0, 0, 0});
    auto sim = simulate(b.spec, "cpu", 1, {}, 50);
    gpu::vec4 pos;
    gpu::vec4 v = after_bounce(*sim, &pos);
    // Free flight from here on: the apex of the lowest point follows exactly.
    double h = (double(pos.z) - kR) + double(v.z) * v.z / (2 * 9.81);
    double ratio = std::sqrt(h / H);
    INFO("H = " << H << " m: sqrt(h/H) = " << ratio << ", LIGGGHTS " << liggghts[k]);
    CHECK(std::abs(ratio - liggghts[k]) < 0.002);
  }
}
