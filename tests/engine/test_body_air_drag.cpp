// Air drag (model extension air_drag) on clump bodies: the drag uses the body's silhouette
// across its velocity, so a falling dumbbell reaches the terminal speed sqrt(2 m g / (rho C_d A))
// of its broadside area when it falls broadside and of one disc when it falls end-on; a lone
// sphere in a clump case falls as the sphere path does.
#include <catch2/catch.hpp>
#include <cmath>

#include "engine_test_support.h"
#include "geometry/projected_area.h"

using namespace repose;
using namespace repose::test;

namespace {

constexpr double kR = 0.005, kDensity = 50, kCd = 1.0, kAir = 1.2, kG = 9.81;

// Vertical speed after `t` s of free fall from rest with drag, for a body of the case.
double fall_speed(CaseSpec spec, double t) {
  spec.gravity = {0, 0, -kG};
  spec.time.dt = 1e-4;
  spec.time.rayleigh_fraction.reset();
  spec.air_drag.drag_coefficient = kCd;
  spec.air_drag.air_density = kAir;
  auto sim = simulate(spec, "cpu", 1, {}, 500);
  sim->advance(uint64_t(std::llround(t / sim->model().dt)));
  return -double(sim->state().bodies.at(0).vel.z);
}

double terminal_speed(double mass, double area) { return std::sqrt(2 * mass * kG / (kAir * kCd * area)); }

}  // namespace

TEST_CASE("silhouette of touching spheres: 2 pi r^2 broadside, pi r^2 end-on (0.5 %)", "[engine][drag]") {
  auto a = projected_areas({{-kR, 0, 0}, {kR, 0, 0}}, {kR, kR});
  CHECK(a[0] == Approx(kPi * kR * kR).epsilon(0.005));
  CHECK(a[1] == Approx(2 * kPi * kR * kR).epsilon(0.005));
  CHECK(a[2] == Approx(2 * kPi * kR * kR).epsilon(0.005));
}

TEST_CASE("a dumbbell falls at the terminal speed of its silhouette: broadside and end-on (1 %)",
          "[engine][drag]") {
  CaseBuilder b;
  int m = b.material(kDensity, 1e6, 0.3);
  b.interaction(m, m, 0.5, 0.5, 0.0);
  int dumbbell = b.clump_template("dumbbell", {{{-kR, 0, 0}, kR}, {{kR, 0, 0}, kR}});
  double mass = kDensity * 2 * 4.0 / 3.0 * kPi * kR * kR * kR;
  SECTION("broadside (axis horizontal)") {
    b.clump(dumbbell, {0, 0, 0}, m);
    double v = fall_speed(b.spec, 2.0);
    double expected = terminal_speed(mass, 2 * kPi * kR * kR);
    INFO("v = " << v << " m/s, terminal " << expected << " m/s");
    CHECK(v == Approx(expected).epsilon(0.01));
  }
  SECTION("end-on (axis vertical)") {
    b.clump(dumbbell, {0, 0, 0}, m, {std::sqrt(0.5), 0, std::sqrt(0.5), 0});
    double v = fall_speed(b.spec, 2.5);
    double expected = terminal_speed(mass, kPi * kR * kR);
    INFO("v = " << v << " m/s, terminal " << expected << " m/s");
    CHECK(v == Approx(expected).epsilon(0.01));
  }
}

TEST_CASE("a lone sphere among clumps falls as a sphere with drag does", "[engine][drag]") {
  CaseBuilder b;
  int m = b.material(kDensity, 1e6, 0.3);
  b.interaction(m, m, 0.5, 0.5, 0.0);
  b.sphere({0, 0, 0}, kR, m);
  int dumbbell = b.clump_template("dumbbell", {{{-kR, 0, 0}, kR}, {{kR, 0, 0}, kR}});
  b.clump(dumbbell, {1, 0, 0}, m);  // far away: no contact
  double v = fall_speed(b.spec, 2.0);
  double expected = terminal_speed(kDensity * 4.0 / 3.0 * kPi * kR * kR * kR, kPi * kR * kR);
  INFO("v = " << v << " m/s, terminal " << expected << " m/s");
  CHECK(v == Approx(expected).epsilon(0.01));
}
