// The tangential dashpot of Hertz-Mindlin, on (EDEM, LIGGGHTS's default) or off per interaction
// (`tangential_damping = false`, LIGGGHTS's `tangential_damping off`), against the theory of a
// sphere resting on a plate and pushed along it below sliding: the tangential spring at the
// contact point oscillates against the sphere's reduced mass m I / (I + m R^2) = 2/7 m, about the
// rolling speed 5/7 v0, undamped when off and at the dashpot's fraction of critical when on.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "case/case_loader.h"
#include "engine_test_support.h"

using namespace repose;
using namespace repose::test;

namespace {

constexpr double kR = 0.01, kDensity = 1000, kG = 9.81, kShear = 1e7, kPoisson = 0.3;

struct Oscillator {
  CaseSpec spec;
  double mass = 0, stiffness = 0, v0 = 0, damping_ratio = 0;
  double frequency() const { return std::sqrt(stiffness / (2.0 / 7.0 * mass)); }
};

// A 10 mm sphere on a steel plane at its static overlap, moving at v0 along x without spin.
Oscillator sphere_pushed_on_plate(double restitution, bool damping) {
  auto text = [&](double z, double v) {
    char sphere[160];
    std::snprintf(sphere, sizeof sphere, "position = [0.0, 0.0, %.17g]\nvelocity = [%.17g, 0.0, 0.0]\n", z, v);
    // A twentieth of the Rayleigh time, ~120 steps per tangential period: the first force evaluation
    // (the spring stretched by v0 dt before it is stored, as LIGGGHTS does) takes (w dt)^2 / 2 of the
    // amplitude, 0.1 % here.
    return std::string("[simulation]\nend_time = 1.0\nrayleigh_fraction = 0.05\n"
                       "[[material]]\nname = \"grain\"\ndensity = 1000.0\nshear_modulus = 1e7\npoisson = 0.3\n"
                       "[[material]]\nname = \"steel\"\npreset = \"q235_steel\"\n"
                       "[[interaction]]\nmaterials = [\"grain\", \"steel\"]\nrestitution = ") +
           std::to_string(restitution) + "\nstatic_friction = 0.8\nrolling_friction = 0.0\n" +
           "tangential_damping = " + (damping ? "true" : "false") + "\n" +
           "[[sphere]]\nmaterial = \"grain\"\nradius = 0.01\n" + sphere +
           "[[wall]]\ntype = \"plane\"\nmaterial = \"steel\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\n";
  };
  Oscillator o;
  o.spec = load_case_from_string(text(kR, 0.0), "tangential.toml");
  o.mass = kDensity * 4.0 / 3.0 * kPi * kR * kR * kR;
  DerivedPairConstants pair = derived_pair_constants(o.spec.materials[0], o.spec.materials[1], o.spec.interactions[0]);
  double overlap = std::pow(o.mass * kG / (4.0 / 3.0 * pair.e_star * std::sqrt(kR)), 2.0 / 3.0);
  o.stiffness = 8 * pair.g_star * std::sqrt(kR * overlap);  // St = 8 G* sqrt(R* dn), R* = R on a wall
  // The dashpot sqrt(St m*) (m* = m on a wall) over critical for the reduced mass 2/7 m.
  o.damping_ratio = damping ? pair.damping * std::sqrt(o.stiffness * o.mass) / (2 * std::sqrt(o.stiffness * 2.0 / 7.0 * o.mass)) : 0;
  // The spring's force amplitude v0 sqrt(St 2/7 m) a quarter of the Coulomb limit: no sliding.
  o.v0 = 0.25 * 0.8 * o.mass * kG / std::sqrt(o.stiffness * 2.0 / 7.0 * o.mass);
  o.spec = load_case_from_string(text(kR - overlap, o.v0), "tangential.toml");
  return o;
}

// The oscillating part of the sphere's speed, vx - 5/7 v0, at every step.
std::vector<double> oscillation(const Oscillator& o, double periods, double& dt) {
  auto sim = simulate(o.spec, "cpu", 1, {}, 1);
  dt = sim->model().dt;
  int steps = int(periods * 2 * kPi / o.frequency() / dt);
  std::vector<double> u;
  for (int k = 0; k < steps; ++k) {
    sim->advance(1);
    u.push_back(sim->state().vel[0].x - 5.0 / 7.0 * o.v0);
  }
  return u;
}

std::vector<double> peaks(const std::vector<double>& u) {
  std::vector<double> p;
  for (size_t k = 1; k + 1 < u.size(); ++k)
    if (u[k] > 0 && u[k] >= u[k - 1] && u[k] > u[k + 1]) p.push_back(u[k]);
  return p;
}

}  // namespace

TEST_CASE("tangential_damping off: a sphere pushed on a plate oscillates at sqrt(7 St / 2m) about 5/7 v0 without decay",
          "[engine][theory]") {
  Oscillator o = sphere_pushed_on_plate(0.5, false);
  REQUIRE(o.spec.interactions[0].tangential_damping == 0.0);
  double dt = 0;
  std::vector<double> u = oscillation(o, 6.3, dt);
  std::vector<double> crossings;  // downward zero crossings, interpolated
  for (size_t k = 1; k < u.size(); ++k)
    if (u[k - 1] > 0 && u[k] <= 0) crossings.push_back(dt * (double(k) - u[k] / (u[k] - u[k - 1])));
  REQUIRE(crossings.size() >= 5);
  double period = (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  std::vector<double> p = peaks(u);
  REQUIRE(p.size() >= 5);
  INFO("period " << period << " s, theory " << 2 * kPi / o.frequency() << " s; first and last peak " << p.front()
                 << ", " << p.back() << ", theory 2/7 v0 = " << 2.0 / 7.0 * o.v0);
  // 1 %: velocity Verlet at ~120 steps per period is ~0.01 % off; the Hertz stiffness moves with
  // the overlap's float rounding.
  CHECK(period == Approx(2 * kPi / o.frequency()).epsilon(0.01));
  // Undamped: the fifth peak keeps the first's amplitude, 2/7 v0 (1 %, the peak seen at a step).
  CHECK(p.back() == Approx(2.0 / 7.0 * o.v0).epsilon(0.01));
  CHECK(p[4] == Approx(p.front()).epsilon(0.01));
}

TEST_CASE("tangential_damping on (the default): the oscillation decays at the dashpot's fraction of critical "
          "(log decrement, 3 %)",
          "[engine][theory]") {
  Oscillator o = sphere_pushed_on_plate(0.8, true);
  REQUIRE(o.spec.interactions[0].tangential_damping == 1.0);
  double dt = 0;
  std::vector<double> p = peaks(oscillation(o, 2.3, dt));
  REQUIRE(p.size() >= 2);
  double zeta = o.damping_ratio;
  double decrement = std::log(p[0] / p[1]), theory = 2 * kPi * zeta / std::sqrt(1 - zeta * zeta);
  INFO("damping ratio " << zeta << ": log decrement " << decrement << ", theory " << theory);
  CHECK(decrement == Approx(theory).epsilon(0.03));  // the peaks are seen at steps (~120 per period)
}

TEST_CASE("tangential_damping takes true or false, named by file, key and line otherwise", "[engine]") {
  std::string text = "[simulation]\nend_time = 1.0\ndt = 1e-5\n"
                     "[[material]]\nname = \"a\"\ndensity = 1000.0\nshear_modulus = 1e7\npoisson = 0.3\n"
                     "[[interaction]]\nmaterials = [\"a\", \"a\"]\nrestitution = 0.5\nstatic_friction = 0.5\n"
                     "rolling_friction = 0.0\ntangential_damping = 0\n"
                     "[[sphere]]\nmaterial = \"a\"\nradius = 0.01\nposition = [0.0, 0.0, 0.0]\n";
  try {
    load_case_from_string(text, "bad.toml");
    FAIL("a number was taken for true or false");
  } catch (const CaseError& e) {
    CHECK_THAT(e.what(), Catch::Contains("bad.toml:14") && Catch::Contains("tangential_damping"));
  }
  CHECK(build_model(load_case_from_string(text.replace(text.find("= 0\n["), 3, "= false"), "off.toml"))
            .pairs[0]
            .tangential_damping == 0.0f);
}
