// Spinning (twisting) friction, `[[interaction]] spinning_friction`: a torque mu_spin R* |Fn|
// about the contact normal against the relative spin, limited so it never reverses the spin.
// Against theory (a sphere spinning on a plate, and on another sphere), the limiter, bit-exact
// backends (spheres and clumps), the default leaving the bytes unchanged, and the case key.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <vector>

#include "case/case_loader.h"
#include "engine_test_support.h"

using namespace repose;
using namespace repose::test;

namespace {

constexpr double kR = 0.01, kDensity = 1000, kG = 9.81;

double sphere_mass() { return kDensity * 4.0 / 3.0 * kPi * kR * kR * kR; }

// The Hertz overlap that carries `load` between a grain (G = 1e7, nu 0.3) and a body of
// effective modulus contribution `other_e` (a plate: steel) at reduced radius r_star.
double static_overlap(double load, double r_star, double other_e) {
  double e_grain = 2e7 * 1.3;
  double e_star = 1 / ((1 - 0.09) / e_grain + (1 - 0.09) / other_e);
  return std::pow(load / (4.0 / 3.0 * e_star * std::sqrt(r_star)), 2.0 / 3.0);
}

// A 10 mm sphere resting on a steel plate at its static overlap, spinning about the vertical.
// No rolling friction: the constant rolling torque would resist the spin as well.
// Grain (material 0) and steel (material 1), friction 0.5, spinning friction mu_spin, gravity.
CaseBuilder grain_and_steel(double mu_spin) {
  CaseBuilder b;
  int grain = b.material(kDensity, 1e7, 0.3);
  int steel = b.material(7800, 8e10, 0.3);
  b.interaction(grain, grain, 0.5, 0.5, 0.0);
  b.interaction(grain, steel, 0.5, 0.5, 0.0);
  for (auto& in : b.spec.interactions) in.spinning_friction = mu_spin;
  b.spec.gravity = {0, 0, -kG};
  b.spec.time.rayleigh_fraction = 0.2;
  return b;
}
constexpr int kGrain = 0, kSteel = 1;

CaseBuilder spinning_on_plate(double mu_spin, double omega_z) {
  CaseBuilder b = grain_and_steel(mu_spin);
  const int grain = kGrain, steel = kSteel;
  double overlap = static_overlap(sphere_mass() * kG, kR, 2 * 8e10 * 1.3);
  b.sphere({0, 0, kR - overlap}, kR, grain, {0, 0, 0}, {0, 0, omega_z});
  b.plane({0, 0, 0}, {0, 0, 1}, steel);
  return b;
}

double spin_z(const Simulation& sim, int i) { return sim.state().omega[i].z; }

}  // namespace

TEST_CASE("spinning friction: a sphere spinning on a plate slows at mu_spin R |Fn| / I (0.1 %) and stops",
          "[engine][theory]") {
  const double mu_spin = 0.1, omega0 = 40.0;
  CaseBuilder b = spinning_on_plate(mu_spin, omega0);
  auto sim = simulate(b.spec, "cpu", 1, {}, 1);
  double dt = sim->model().dt;
  // |Fn| = m g at rest, I = 2/5 m R^2: d omega / dt = 2.5 mu_spin g / R = 245 rad/s^2.
  double rate = mu_spin * kR * sphere_mass() * kG / (0.4 * sphere_mass() * kR * kR);
  double stop_time = omega0 / rate;
  int n1 = int(0.2 * stop_time / dt), n2 = int(0.8 * stop_time / dt);
  std::vector<double> w;
  int steps = int(1.2 * stop_time / dt);
  bool reversed = false, monotone = true;
  for (int k = 0; k < steps; ++k) {
    sim->advance(1);
    w.push_back(spin_z(*sim, 0));
    reversed |= w.back() < 0;
    if (k > 0) monotone &= w[k] <= w[k - 1];
  }
  // The normal force is the weight to within the Hertz oscillation left by the float start
  // (measured: 0.007 % off), so the slope must match the theory to 0.1 %.
  double measured = (w[n1] - w[n2]) / ((n2 - n1) * dt);
  INFO("measured " << measured << " rad/s^2, theory " << rate);
  CHECK(measured == Approx(rate).epsilon(0.001));
  CHECK(w[0] < omega0);
  CHECK_FALSE(reversed);
  CHECK(monotone);
  CHECK(w.back() < 1e-6 * omega0);  // stopped: the limiter halves the last of the spin each step
  // The sphere stayed where it was: the twist makes no tangential force.
  CHECK(std::abs(sim->state().pos[0].x) < 1e-9);
  CHECK(std::abs(sim->state().vel[0].x) < 1e-9);
}

TEST_CASE("spinning friction: on another sphere the torque uses R* = R/2 (0.1 %)", "[engine][theory]") {
  // A sphere spinning on top of a resting one on the plate: the top one slows at
  // mu_spin (R/2) m g / (2/5 m R^2) = 1.25 mu_spin g / R; the bottom one is held by the plate
  // (whose cap, mu_spin R 2 m g, is four times the torque it receives).
  const double mu_spin = 0.2, omega0 = 30.0;
  CaseBuilder b = grain_and_steel(mu_spin);
  const int grain = kGrain, steel = kSteel;
  double m = sphere_mass();
  double floor_overlap = static_overlap(2 * m * kG, kR, 2 * 8e10 * 1.3);
  double pair_overlap = static_overlap(m * kG, kR / 2, 2e7 * 1.3);
  double z0 = kR - floor_overlap;
  b.sphere({0, 0, z0}, kR, grain);
  b.sphere({0, 0, z0 + 2 * kR - pair_overlap}, kR, grain, {0, 0, 0}, {0, 0, omega0});
  b.plane({0, 0, 0}, {0, 0, 1}, steel);
  auto sim = simulate(b.spec, "cpu", 1, {}, 1);
  double dt = sim->model().dt;
  double rate = 1.25 * mu_spin * kG / kR;
  double stop_time = omega0 / rate;
  int n1 = int(0.2 * stop_time / dt), n2 = int(0.8 * stop_time / dt);
  std::vector<double> top, bottom;
  for (int k = 0; k <= n2; ++k) {
    sim->advance(1);
    top.push_back(spin_z(*sim, 1));
    bottom.push_back(std::abs(spin_z(*sim, 0)));
  }
  double measured = (top[n1] - top[n2]) / ((n2 - n1) * dt);
  INFO("measured " << measured << " rad/s^2, theory " << rate);
  CHECK(measured == Approx(rate).epsilon(0.001));
  // The bottom sphere creeps only by the limiter's slip: far below 1 % of the top's spin.
  CHECK(*std::max_element(bottom.begin(), bottom.end()) < 0.01 * omega0);
}

TEST_CASE("spinning friction: the limiter never turns a spin over, even when it is far below the cap",
          "[engine]") {
  // mu_spin 50: the cap alone would stop 0.5 rad/s in 4 us, a fifteenth of a step, so the
  // limiter does the stopping.
  CaseBuilder b = spinning_on_plate(50.0, 0.5);
  auto sim = simulate(b.spec, "cpu", 1, {}, 1);
  double prev = 0.5;
  for (int k = 0; k < 400; ++k) {
    sim->advance(1);
    double w = spin_z(*sim, 0);
    REQUIRE(w >= 0.0);
    REQUIRE(w <= prev);
    prev = w;
  }
  CHECK(prev < 1e-6);
}

namespace {

// Spheres falling onto each other, spinning friction 0.3.
CaseSpec spinning_cloud() {
  CaseSpec spheres = seeded_cloud(150, 91, 2.0, 0.05);
  for (auto& in : spheres.interactions) in.spinning_friction = 0.3;
  return spheres;
}

// Clumps of three unequal spheres tumbling onto the floor, spinning, spinning friction 0.2.
CaseSpec spinning_clumps() {
  CaseBuilder b;
  int grain = b.material(1000, 5e6, 0.3);
  int steel = b.material(7800, 8e10, 0.3);
  b.interaction(grain, grain, 0.5, 0.4, 0.05);
  b.interaction(grain, steel, 0.6, 0.3, 0.02);
  for (auto& in : b.spec.interactions) in.spinning_friction = 0.2;
  b.spec.gravity = {0, 0, -9.81};
  b.spec.time.rayleigh_fraction = 0.2;
  int t = b.clump_template("lumpy", lumpy_clump());
  for (int k = 0; k < 12; ++k)
    b.clump(t, {0.03 * (k % 3), 0.03 * ((k / 3) % 2), 0.012 + 0.03 * (k / 6)}, grain,
            {0.9, 0.1 * k, -0.3, 0.2}, {0, 0, 0}, {3.0 * k - 15, 2.0, 20.0 - 3 * k});
  b.plane({0, 0, 0}, {0, 0, 1}, steel);
  b.plane({-0.012, 0, 0}, {1, 0, 0}, steel);
  return b.spec;
}

}  // namespace

TEST_CASE("spinning friction: identical on lavapipe and the CPU twin (spheres and clumps)", "[engine][bitexact]") {
  CaseSpec spheres = spinning_cloud(), clumps = spinning_clumps();
  for (const CaseSpec* spec : {&spheres, &clumps}) {
    auto reference = simulate(*spec, "cpu", 1, {}, 25);
    reference->advance(1200);
    for (const char* text : {"contact", "rows,wg=32"}) {
      for (const char* backend : {"cpu", "vulkan"}) {
        auto sim = simulate(*spec, backend, 2, KernelVariant::parse(text), 25);
        sim->advance(1200);
        std::string which;
        bool same = same_state(reference->state(), sim->state(), &which);
        INFO((spec == &spheres ? "spheres " : "clumps ") << backend << " " << text << " differs in " << which);
        CHECK(same);
      }
    }
    CHECK_THROWS_AS(simulate(*spec, "cpu", 1, KernelVariant::parse("contact,lean")), std::invalid_argument);
  }
}

TEST_CASE("spinning friction: the same bytes when the hardware flushes denormals, as some GPUs do",
          "[engine][bitexact]") {
  // The limiter halves a spin step after step: without a floor it walks the spin through the
  // denormal range, where such a GPU reads zero.
  CaseBuilder b = spinning_on_plate(50.0, 0.5);
  CaseSpec spheres = spinning_cloud(), clumps = spinning_clumps();
  for (const CaseSpec* spec : {&b.spec, &spheres, &clumps}) {
    auto reference = simulate(*spec, "cpu", 2, {}, 25);
    reference->advance(1200);
    std::string which;
    bool same = same_state(reference->state(), simulate_flushing_denormals(*spec, 1200)->state(), &which);
    INFO("differs in " << which);
    CHECK(same);
  }
}

// The limiter counts touching contacts, not list entries, so as for every other option the skin
// and the moments of rebuilding change no byte (docs/engineering.md, neighbour search).
TEST_CASE("spinning friction: the neighbour skin and the rebuild interval leave every byte unchanged",
          "[engine][bitexact]") {
  CaseSpec spheres = spinning_cloud(), clumps = spinning_clumps();
  for (const CaseSpec* spec : {&spheres, &clumps}) {
    double skin = build_model(*spec).skin;
    auto run = [&](double s, int interval) { return simulate_with_list(*spec, s, interval, 1200, {}, 25); };
    auto reference = run(skin, 0);
    REQUIRE(reference->contacts() > 10);
    for (auto [s, interval] : {std::pair{0.3 * skin, 0}, std::pair{4.0 * skin, 0}, std::pair{skin, 1}}) {
      auto other = run(s, interval);
      INFO((spec == &spheres ? "spheres" : "clumps") << ", skin " << s << " m, rebuild interval " << interval);
      CHECK(other->rebuilds() != reference->rebuilds());
      CHECK(same_bytes(reference->state().pos, other->state().pos));
      CHECK(same_bytes(reference->state().vel, other->state().vel));
      CHECK(same_bytes(reference->state().omega, other->state().omega));
      CHECK(same_bytes(reference->state().torque, other->state().torque));
      CHECK(same_bytes(reference->state().bodies, other->state().bodies));
    }
  }
}

TEST_CASE("spinning friction 0 (the default) leaves the bytes unchanged", "[engine][bitexact]") {
  // The same cloud with the option's code path switched on (a third material that never meets
  // the grains has spinning friction, so the kernel flag is set) and off: the same bytes, on
  // both backends. (Checked once against the binary built before the option existed: the state
  // files of cases/settle_box.toml after 2,000 steps (cpu, lavapipe, and with rolling = "epsd")
  // and of cases/cabbage_settle.toml (clumps) after 300 steps were identical to the byte.)
  CaseSpec off = seeded_cloud(120, 5, 2.0, 0.05);
  CaseSpec on = off;
  Material spare = on.materials[0];
  spare.name = "spare";
  on.materials.push_back(spare);
  Interaction unused = on.interactions[0];
  unused.material_a = unused.material_b = int(on.materials.size()) - 1;
  unused.spinning_friction = 0.5;
  on.interactions.push_back(unused);
  REQUIRE((build_model(on).flags & gpu::kFlagSpinningFriction) != 0);
  REQUIRE((build_model(off).flags & gpu::kFlagSpinningFriction) == 0);
  for (const char* backend : {"cpu", "vulkan"}) {
    auto a = simulate(off, backend, 2, {}, 25);
    auto b = simulate(on, backend, 2, {}, 25);
    a->advance(800);
    b->advance(800);
    std::string which;
    bool same = same_state(a->state(), b->state(), &which);
    INFO(backend << " differs in " << which);
    CHECK(same);
  }
}

TEST_CASE("spinning_friction case key: read per interaction, negative named by file and line, and runs keep full contact entries", "[case]") {
  std::string base = R"([simulation]
end_time = 0.1
rayleigh_fraction = 0.2

[[material]]
preset = "cabbage"

[[sphere]]
material = "cabbage"
radius = 0.05
position = [0, 0, 0.1]

[[interaction]]
materials = ["cabbage", "cabbage"]
preset = ["cabbage", "cabbage"]
)";
  CaseSpec spec = load_case_from_string(base + "spinning_friction = 0.04\n", "cases/spin.toml");
  CHECK(spec.interactions.at(0).spinning_friction == 0.04);
  CHECK(build_model(spec).pairs.at(0).spinning_friction == 0.04f);
  CaseSpec plain = load_case_from_string(base, "cases/spin.toml");
  CHECK(plain.interactions.at(0).spinning_friction == 0.0);
  // The default variant: lean on Vulkan unless torques are stored per contact; never on cpu.
  CHECK_FALSE(KernelVariant::fastest_for("vulkan", build_model(spec)).lean);
  CHECK(KernelVariant::fastest_for("vulkan", build_model(plain)).lean);
  CHECK_FALSE(KernelVariant::fastest_for("cpu", build_model(plain)).lean);
  CHECK_THROWS_WITH(load_case_from_string(base + "spinning_friction = -0.1\n", "cases/spin.toml"),
                    Catch::Matchers::StartsWith("cases/spin.toml:16: interaction[0].spinning_friction: "));
}
