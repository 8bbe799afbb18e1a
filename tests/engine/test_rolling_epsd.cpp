// EDEM's type C rolling resistance (elastic-plastic spring-dashpot, `[contact] rolling = "epsd"`)
// against the theory of a sphere rolling without slip on a plate: the rolling spring alone makes
// a harmonic oscillator about the contact point, its dashpot damps it at eta_r of critical, and
// on an incline it holds below tan(beta) = mu_r and rolls at the capped torque above. Plus the
// determinism of the stored springs (carried over rebuilds, both backends) and the case keys.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "case/case_loader.h"
#include "engine_test_support.h"

using namespace repose;
using namespace repose::test;

namespace {

constexpr double kR = 0.01, kDensity = 1000, kG = 9.81;

struct PlateRig {
  CaseBuilder b;
  double mass = 0, overlap = 0, normal_stiffness = 0;
};

// A 10 mm sphere resting on a plate at its static overlap, gravity tilted by beta about y (the
// downhill direction is +x), rolling without slip at angular speed omega_y.
PlateRig sphere_on_plate(double mu_r, double eta_r, double beta, double omega_y) {
  PlateRig rig;
  CaseBuilder& b = rig.b;
  int grain = b.material(kDensity, 1e7, 0.3);
  int steel = b.material(7800, 8e10, 0.3);
  b.interaction(grain, grain, 0.5, 0.8, mu_r);
  b.interaction(grain, steel, 0.5, 0.8, mu_r);
  b.spec.gravity = {kG * std::sin(beta), 0, -kG * std::cos(beta)};
  b.spec.time.rayleigh_fraction = 0.2;
  b.spec.contact.rolling = RollingModel::ElasticPlastic;
  b.spec.contact.rolling_damping = eta_r;
  rig.mass = kDensity * 4.0 / 3.0 * kPi * kR * kR * kR;
  double e_grain = 2e7 * 1.3, e_steel = 2 * 8e10 * 1.3;
  double e_star = 1 / ((1 - 0.09) / e_grain + (1 - 0.09) / e_steel);
  double weight = rig.mass * kG * std::cos(beta);
  rig.overlap = std::pow(weight / (4.0 / 3.0 * e_star * std::sqrt(kR)), 2.0 / 3.0);
  rig.normal_stiffness = weight / rig.overlap;  // the Hertz secant stiffness the law uses
  b.sphere({0, 0, kR - rig.overlap}, kR, grain, {omega_y * kR, 0, 0}, {0, omega_y, 0});
  b.plane({0, 0, 0}, {0, 0, 1}, steel);
  return rig;
}

// The rolling spring's stiffness and the rocking frequency about the contact point.
double rolling_stiffness(const PlateRig& rig, double mu_r) {
  return 2.25 * rig.normal_stiffness * (mu_r * kR) * (mu_r * kR);
}
double rocking_frequency(const PlateRig& rig, double mu_r) {
  double inertia_contact = 1.4 * rig.mass * kR * kR;
  return std::sqrt(rolling_stiffness(rig, mu_r) / inertia_contact);
}

// omega_y at every step for `steps` steps.
std::vector<double> spin_series(Simulation& sim, int steps) {
  std::vector<double> w;
  for (int k = 0; k < steps; ++k) {
    sim.advance(1);
    w.push_back(sim.state().omega[0].y);
  }
  return w;
}

}  // namespace

TEST_CASE("EPSD: undamped, a sphere rocks on a plate at sqrt(k_r / (7/5 m R^2)) (2 %)", "[engine][theory]") {
  const double mu_r = 0.05;
  PlateRig probe = sphere_on_plate(mu_r, 0.0, 0.0, 0.0);
  double w_n = rocking_frequency(probe, mu_r);
  // Amplitude 30 % of the spring's cap: the spring never slips, the motion is harmonic.
  double theta_cap = mu_r * kR * probe.mass * kG / rolling_stiffness(probe, mu_r);
  double omega0 = 0.3 * theta_cap * w_n;
  PlateRig rig = sphere_on_plate(mu_r, 0.0, 0.0, omega0);
  auto sim = simulate(rig.b.spec, "cpu", 1, {}, 1);
  double dt = sim->model().dt;
  int steps = int(3.5 * 2 * kPi / w_n / dt);
  std::vector<double> w = spin_series(*sim, steps);
  // Downward zero crossings of omega_y (interpolated) give the period.
  std::vector<double> crossings;
  for (size_t k = 1; k < w.size(); ++k)
    if (w[k - 1] > 0 && w[k] <= 0) crossings.push_back(dt * (double(k) - w[k] / (w[k] - w[k - 1])));
  REQUIRE(crossings.size() >= 3);
  double period = (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  double peak = *std::max_element(w.begin() + steps / 2, w.end());
  INFO("period " << period << " s, theory " << 2 * kPi / w_n << " s; late peak " << peak << " vs " << omega0);
  CHECK(period == Approx(2 * kPi / w_n).epsilon(0.02));
  // Undamped: the late peaks keep the initial spin (energy kept within 2 %).
  CHECK(peak == Approx(omega0).epsilon(0.02));
}

TEST_CASE("EPSD: the rolling dashpot damps the rocking at eta_r of critical (log decrement, 3 %)",
          "[engine][theory]") {
  const double mu_r = 0.05, eta = 0.2;
  PlateRig probe = sphere_on_plate(mu_r, eta, 0.0, 0.0);
  double w_n = rocking_frequency(probe, mu_r);
  double theta_cap = mu_r * kR * probe.mass * kG / rolling_stiffness(probe, mu_r);
  PlateRig rig = sphere_on_plate(mu_r, eta, 0.0, 0.3 * theta_cap * w_n);
  auto sim = simulate(rig.b.spec, "cpu", 1, {}, 1);
  double dt = sim->model().dt;
  std::vector<double> w = spin_series(*sim, int(2.2 * 2 * kPi / w_n / dt));
  // Successive positive peaks of omega_y, one damped period apart.
  std::vector<double> peaks;
  for (size_t k = 1; k + 1 < w.size(); ++k)
    if (w[k] > 0 && w[k] >= w[k - 1] && w[k] > w[k + 1]) peaks.push_back(w[k]);
  REQUIRE(peaks.size() >= 2);
  double decrement = std::log(peaks[0] / peaks[1]);
  double theory = 2 * kPi * eta / std::sqrt(1 - eta * eta);
  INFO("peaks " << peaks[0] << ", " << peaks[1] << ": log decrement " << decrement << ", theory " << theory);
  CHECK(decrement == Approx(theory).epsilon(0.03));
}

TEST_CASE("EPSD: a sphere stays on an incline below tan(beta) = mu_r and rolls at 5/7 g (sin b - mu_r cos b) "
          "above (1 %)",
          "[engine][theory]") {
  const double mu_r = 0.1;
  SECTION("holds at tan(beta) = mu_r / 2") {
    PlateRig rig = sphere_on_plate(mu_r, 0.3, std::atan(0.5 * mu_r), 0.0);
    auto sim = simulate(rig.b.spec, "cpu", 1, {}, 50);
    sim->advance(uint64_t(0.5 / sim->model().dt));
    double x = sim->state().pos[0].x, v = sim->state().vel[0].x;
    // Elastic wind-up only: half the cap's rotation, theta = M / k_r (5 %: the lever is R - dn/2).
    double windup = 0.5 * mu_r * kR * rig.mass * kG * std::cos(std::atan(0.5 * mu_r)) / rolling_stiffness(rig, mu_r) * kR;
    INFO("x = " << x << " m after 0.5 s (elastic wind-up " << windup << " m), v = " << v);
    CHECK(x == Approx(windup).epsilon(0.05));
    CHECK(std::abs(v) < 1e-4);
  }
  SECTION("rolls at tan(beta) = 2 mu_r") {
    double beta = std::atan(2 * mu_r);
    PlateRig rig = sphere_on_plate(mu_r, 0.3, beta, 0.0);
    auto sim = simulate(rig.b.spec, "cpu", 1, {}, 50);
    double t = 0.3;
    sim->advance(uint64_t(t / sim->model().dt));
    t = sim->time();
    double a = 5.0 / 7.0 * kG * (std::sin(beta) - mu_r * std::cos(beta));
    double x = sim->state().pos[0].x;
    INFO("x = " << x << " m after " << t << " s; theory 0.5 a t^2 = " << 0.5 * a * t * t);
    CHECK(x == Approx(0.5 * a * t * t).epsilon(0.01));
  }
}

TEST_CASE("EPSD: rolling springs carried over rebuilds, identical on lavapipe and the CPU twin",
          "[engine][bitexact]") {
  // A stack of touching spheres spinning at random, collapsing under gravity onto the floor.
  CaseSpec spec = seeded_cloud(150, 77, 2.0, 0.05);
  for (auto& sphere : spec.spheres) sphere.velocity = {0, 0, 0};
  spec.contact.rolling = RollingModel::ElasticPlastic;
  spec.contact.rolling_damping = 0.3;
  auto reference = simulate(spec, "cpu", 1, {}, 25);
  reference->advance(1500);
  const HostState& s = reference->state();
  // Springs that outlived a rebuild: loaded, on contacts older than the current list.
  uint32_t since_build = s.control[gpu::kCtlStepsSinceBuild];
  size_t loaded = 0, carried = 0;
  for (size_t c = 0; c < s.rolling_spring.size(); ++c) {
    const auto& r = s.rolling_spring[c];
    bool is_loaded = r.x != 0 || r.y != 0 || r.z != 0;
    loaded += is_loaded ? 1 : 0;
    carried += is_loaded && s.history[c].w > float(since_build) ? 1 : 0;
  }
  INFO(loaded << " of " << s.rolling_spring.size() << " contacts with a loaded rolling spring, " << carried
              << " of them older than the list (" << reference->rebuilds() << " rebuilds)");
  CHECK(carried > 10);
  CHECK(reference->rebuilds() > 2);
  for (const char* text : {"contact", "rows,wg=32"}) {
    for (const char* backend : {"cpu", "vulkan"}) {
      auto sim = simulate(spec, backend, 2, KernelVariant::parse(text), 25);
      sim->advance(1500);
      std::string which;
      bool same = same_state(s, sim->state(), &which);
      INFO(backend << " " << text << " differs in " << which);
      CHECK(same);
    }
  }
  CHECK_THROWS_AS(simulate(spec, "cpu", 1, KernelVariant::parse("contact,lean")), std::invalid_argument);
}

TEST_CASE("EPSD case keys: rolling = \"epsd\" with rolling_damping; misuse named by key", "[case]") {
  std::string base = R"([simulation]
end_time = 0.1
rayleigh_fraction = 0.2

[[material]]
preset = "cabbage"

[[interaction]]
materials = ["cabbage", "cabbage"]
preset = ["cabbage", "cabbage"]

[[sphere]]
material = "cabbage"
radius = 0.05
position = [0, 0, 0.1]

[contact]
)";
  CaseSpec spec = load_case_from_string(base + "rolling = \"epsd\"\nrolling_damping = 0.25\n", "cases/epsd.toml");
  CHECK(spec.contact.rolling == RollingModel::ElasticPlastic);
  CHECK(spec.contact.rolling_damping == 0.25);
  CHECK(load_case_from_string(base + "rolling = \"epsd\"\n", "cases/epsd.toml").contact.rolling_damping == 0.3);
  CHECK_THROWS_WITH(load_case_from_string(base + "rolling_damping = 0.25\n", "cases/epsd.toml"),
                    Catch::Matchers::StartsWith("cases/epsd.toml:18: contact.rolling_damping: "));
  CHECK_THROWS_WITH(load_case_from_string(base + "rolling = \"epsd\"\nrolling_damping = -1\n", "cases/epsd.toml"),
                    Catch::Matchers::StartsWith("cases/epsd.toml:19: contact.rolling_damping: "));
}
