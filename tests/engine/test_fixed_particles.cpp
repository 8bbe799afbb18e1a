// Fixed particles (`fixed = true`): they take part in contacts as an infinite mass and never move.
// A sphere settles on a fixed sphere bed; a collision with a fixed sphere is Hertz's with the
// moving sphere's mass (the wall limit); fixed bodies keep their bytes; both backends agree.
#include <catch2/catch.hpp>

#include "case/case_loader.h"
#include "case/case_error.h"
#include "engine_test_support.h"

using namespace repose;
using namespace repose::test;

namespace {

// The contact time of a sphere (radius R, velocity v towards -x) hitting a fixed sphere of radius
// Rf touching the plane x = 0 from behind, or that plane as a wall (Rf = 0); and its rebound
// speed ratio. The moving sphere stays near the origin, where float positions resolve its
// overlap (~1e-4 m) finely.
void collide(double Rf, double& contact_time, double& rebound) {
  CaseBuilder b;
  int g = b.material(2500, 1e8, 0.3);
  b.interaction(g, g, 0.5, 0.0, 0.0);
  const double R = 0.01, v = 0.5;
  if (Rf > 0) {
    b.spec.spheres.push_back({});
    SphereSpec& s = b.spec.spheres.back();
    s.position = {-Rf, 0, 0};
    s.radius = Rf;
    s.material = g;
    s.fixed = true;
  } else {
    b.plane({0, 0, 0}, {1, 0, 0}, g);
  }
  b.sphere({R + 1e-5, 0, 0}, R, g, {-v, 0, 0});
  b.spec.time.rayleigh_fraction = 0.01;
  auto sim = simulate(b.spec, "cpu", 1, {}, 1);
  int moving = Rf > 0 ? 1 : 0;
  double first = -1, last = -1;
  for (int s = 0; s < 400000; ++s) {
    sim->advance(1);
    bool touching = double(sim->state().pos[moving].x) < R;
    if (touching && first < 0) first = sim->time();
    if (touching) last = sim->time();
    if (first >= 0 && !touching) break;
  }
  contact_time = last - first + sim->model().dt;
  rebound = double(sim->state().vel[moving].x) / v;
  if (Rf > 0) CHECK(sim->state().pos[0].x == float(-Rf));  // the fixed sphere never moved
}

}  // namespace

// Hertz with m* = m (the fixed sphere's mass is infinite) and R* = R Rf / (R + Rf); e returned.
TEST_CASE("a sphere hitting a fixed sphere: Hertz's contact time with m* = m, restitution e (1 %)", "[engine][fixed]") {
  const double R = 0.01;
  double t_wall = 0, e_wall = 0;
  collide(0, t_wall, e_wall);
  for (double Rf : {0.01, 1.0}) {
    // Hertz's contact time goes as (m*^2 / (E*^2 R* v))^(1/5) (times a factor of e alone), so
    // against the wall (R* = R, m* = m) it is longer by (R / R*)^(1/5) when m* = m.
    double R_star = R * Rf / (R + Rf);
    double t_fixed = 0, e_fixed = 0;
    collide(Rf, t_fixed, e_fixed);
    INFO("fixed sphere of radius " << Rf << ": contact " << t_fixed << " s (wall " << t_wall << " s), rebound "
                                   << e_fixed << " (wall " << e_wall << ")");
    CHECK(e_fixed == Approx(0.5).epsilon(0.01));  // 1 %: the restitution test's tolerance at this dt
    CHECK(t_fixed / t_wall == Approx(std::pow(R / R_star, 0.2)).epsilon(0.01));
  }
}

// A sphere dropped into the hollow between four fixed spheres of a square bed comes to rest
// sqrt(2) R above their centres (less the overlaps of its weight), and the bed never moves.
TEST_CASE("a sphere settles on a fixed sphere bed, which keeps its bytes", "[engine][fixed]") {
  CaseBuilder b;
  int g = b.material(1000, 1e7, 0.3);
  b.interaction(g, g, 0.3, 0.5, 0.02);
  b.spec.gravity = {0, 0, -9.81};
  b.spec.time.rayleigh_fraction = 0.2;
  const double R = 0.01;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      b.sphere({(i - 1.5) * 2 * R, (j - 1.5) * 2 * R, 0}, R, g);
      b.spec.spheres.back().fixed = true;
    }
  b.sphere({0, 0, 3 * R}, R, g);  // above the hollow between the four central bed spheres
  auto sim = simulate(b.spec, "cpu", 2);
  HostState start = sim->state();
  sim->advance(uint64_t(1.0 / sim->model().dt));
  const HostState& s = sim->state();
  for (int k = 0; k < 16; ++k) {
    CHECK(std::memcmp(&s.pos[k], &start.pos[k], sizeof(gpu::vec4)) == 0);
    CHECK(std::memcmp(&s.vel[k], &start.vel[k], sizeof(gpu::vec4)) == 0);
  }
  // At rest in the central hollow: four contacts along (+-R, +-R, h) carry its weight.
  double h = s.pos[16].z;
  CHECK(std::abs(double(s.pos[16].x)) < 1e-6);  // symmetric: only rounding moves it sideways
  CHECK(std::abs(double(s.pos[16].y)) < 1e-6);
  CHECK(sim->kinetic_energy().total() < 1e-10);
  // Overlap per contact from Hertz, each carrying m g / 4 along its normal (angle 45 deg).
  double m = 1000 * 4.0 / 3.0 * kPi * R * R * R, E = 2e7 * 1.3, E_star = E / (2 * (1 - 0.09));
  double fn = m * 9.81 / 4 / std::cos(kPi / 4);
  double dn = std::pow(fn / (4.0 / 3.0 * E_star * std::sqrt(R / 2)), 2.0 / 3.0);
  double expected = std::sqrt((2 * R - dn) * (2 * R - dn) - 2 * R * R);
  INFO("rest height " << h << " m above the bed's centres; expected " << expected);
  CHECK(h == Approx(expected).epsilon(1e-4));  // the overlaps lower it by 5e-4; float positions 1e-7
}

// Lumpy clumps and spheres falling onto a bed of fixed clumps and fixed spheres, on a floor.
TEST_CASE("fixed clumps and spheres: bit-exact on lavapipe and the CPU twin, and they never move",
          "[engine][fixed][bitexact]") {
  CaseSpec spec = clump_pile();
  // The first 16 clumps and the first 8 spheres (the lowest layer) become the fixed bed.
  for (size_t k = 0; k < 16; ++k) {
    spec.bodies[k].fixed = true;
    spec.bodies[k].velocity = spec.bodies[k].angular_velocity = {0, 0, 0};
  }
  for (size_t k = 0; k < 8; ++k) spec.spheres[k].fixed = true;
  auto reference = simulate(spec, "cpu", 1);
  const HostState start = reference->state();
  reference->advance(1500);
  REQUIRE(reference->contacts() > 50);
  const HostState& end = reference->state();
  for (size_t b = 0; b < end.bodies.size(); ++b) {
    bool fixed = (b >= 20 && b < 36) || b < 8;  // lone spheres are the first 20 bodies
    // pos, vel, quat, ang_mom, omega: the first five vec4 (force and torque are still summed)
    if (fixed) CHECK(std::memcmp(&end.bodies[b], &start.bodies[b], 5 * sizeof(gpu::vec4)) == 0);
  }
  std::string which;
  for (const char* v : {"contact,lean", "rows,full"}) {
    auto other = simulate(spec, "vulkan", 1, KernelVariant::parse(v));
    other->advance(1500);
    INFO(v << ": first difference in " << which);
    CHECK(same_state(reference->state(), other->state(), &which));
  }
}

TEST_CASE("fixed = true on spheres, clumps, fills and lattices, a fixed particle given a velocity is refused",
          "[case][fixed]") {
  std::string base = R"([simulation]
end_time = 0.1
dt = 1e-5
[[material]]
preset = "cabbage"
[[interaction]]
materials = ["cabbage", "cabbage"]
preset = ["cabbage", "cabbage"]
[[template]]
name = "pair"
builtin = "cabbage"
)";
  CaseSpec spec = load_case_from_string(base + R"([[sphere]]
material = "cabbage"
radius = 0.01
position = [1, 0, 0]
fixed = true
[[clump]]
template = "pair"
material = "cabbage"
position = [0, 0, 0]
fixed = true
[[lattice]]
material = "cabbage"
type = "sc"
min = [2, 0, 0]
max = [2.1, 0.1, 0.02]
spacing = 0.02
radius = 0.01
fixed = true
)",
                                        "fixed.toml");
  REQUIRE(!spec.spheres.empty());
  for (const SphereSpec& s : spec.spheres) CHECK(s.fixed);
  CHECK(spec.bodies.at(0).fixed);
  std::string message;
  try {
    load_case_from_string(base + "[[sphere]]\nmaterial = \"cabbage\"\nradius = 0.01\nposition = [1, 0, 0]\n"
                                 "velocity = [0, 0, 1]\nfixed = true\n",
                          "bad.toml");
  } catch (const CaseError& e) {
    message = e.what();
  }
  CHECK_THAT(message, Catch::Matchers::StartsWith("bad.toml:16: sphere[0].velocity") &&
                          Catch::Matchers::Contains("never moves"));
}
