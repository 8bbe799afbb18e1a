// Tilting-plate and inclined-rolling experiments against theory.
#include <catch2/catch.hpp>

#include "../engine/engine_test_support.h"
#include "case/case_loader.h"
#include "experiments/roll.h"
#include "experiments/tilt.h"

using namespace repose;
using namespace repose::test;

namespace {

// A body on a 0.6 m square rectangle plate that tilts about y at 1 deg/s.
CaseSpec tilt_case(double mu_s, double mu_r, bool four_spheres) {
  CaseBuilder b;
  int grain = b.material(1000, 1e6, 0.3);
  int steel = b.material(7800, 8e10, 0.3);
  b.interaction(grain, steel, 0.5, mu_s, mu_r);
  b.spec.gravity = {0, 0, -9.81};
  b.spec.time.rayleigh_fraction = 0.2;
  const double r = 0.02;
  if (four_spheres) b.four_sphere_body(r, grain);
  else b.sphere({0, 0, r * 0.999}, r, grain);
  b.level_plate("plate", 0.6, steel);
  b.spec.experiment.type = four_spheres ? "slide" : "roll";
  RollSettings& tilt = edit_settings<RollSettings>(b.spec.experiment);  // a slide reads its tilt keys
  tilt.method = "tilt";
  tilt.settle_time = 0.3;
  b.spec.experiment.max_time = 60;
  return b.spec;
}

}  // namespace

TEST_CASE("tilt test: a four-sphere body slides at tan(alpha) = mu_s within 1 degree", "[experiments][slide]") {
  for (double mu_s : {0.3, 0.6}) {
    TiltResult r = run_tilt(tilt_case(mu_s, 0.05, true));
    double expected = std::atan(mu_s) * 180 / kPi;
    INFO("mu_s = " << mu_s << ": onset at " << r.onset_angle_deg << " deg, atan(mu_s) = " << expected);
    // The 1 mm onset distance is reached a few tenths of a degree after slip begins at 1 deg/s.
    CHECK(std::abs(r.onset_angle_deg - expected) < 1.0);
    CHECK(r.onset_angle_deg >= expected - 0.05);  // never before Coulomb allows it
    CHECK(r.rolled_fraction < 0.2);               // it slid
  }
}

TEST_CASE("tilt test: a sphere with constant rolling torque starts to roll at tan(alpha) = mu_r", "[experiments][roll]") {
  // Rolling without slip against the torque mu_r N R accelerates when
  // m g sin(a) > mu_r m g cos(a): onset at tan(alpha) = mu_r, before sliding when mu_r < mu_s.
  TiltResult r = run_tilt(tilt_case(0.5, 0.1, false));
  double expected = std::atan(0.1) * 180 / kPi;
  INFO("onset at " << r.onset_angle_deg << " deg, atan(mu_r) = " << expected << ", rolled fraction " << r.rolled_fraction);
  CHECK(std::abs(r.onset_angle_deg - expected) < 1.0);
  CHECK(r.rolled_fraction > 0.8);  // it rolled
}

TEST_CASE("tilt test with onset_speed: a sphere starts to roll where rigid-body theory says, either rolling model",
          "[experiments][roll]") {
  // Past tan(a0) = mu_r a rolling sphere accelerates at g (sin a - mu_r cos a) / 1.4
  // ~= g w t / (1.4 cos a0) with the tilt rate w, so it reaches speed v after
  // t = sqrt(2.8 cos(a0) v / (g w)): onset at a0 + w t. The 1 mm onset distance comes much
  // earlier on a soft body (creep under the constant torque, the EPSD spring's elastic roll).
  const double mu_r = 0.05, v = 0.01, w = kPi / 180;  // 1 deg/s
  double a0 = std::atan(mu_r);
  double expected = (a0 + w * std::sqrt(2.8 * std::cos(a0) * v / (9.81 * w))) * 180 / kPi;
  for (RollingModel model : {RollingModel::ConstantTorque, RollingModel::ElasticPlastic}) {
    CaseSpec spec = tilt_case(0.5, mu_r, false);
    spec.contact.rolling = model;
    if (model == RollingModel::ElasticPlastic) spec.interactions[0].spinning_friction = mu_r;
    edit_settings<RollSettings>(spec.experiment).onset_speed = v;
    TiltResult r = run_tilt(spec);
    INFO((model == RollingModel::ElasticPlastic ? "epsd" : "constant torque")
         << ": onset at " << r.onset_angle_deg << " deg, theory " << expected);
    // 0.02 deg, two samples (0.01 s, 0.01 deg apart; measured within 0.002 deg with both models).
    CHECK(r.onset_angle_deg == Approx(expected).margin(0.02));
    CHECK(r.rolled_fraction > 0.8);
  }
}

TEST_CASE("shipped slide case: the four-sphere group slides on PVC at atan(0.34) within 1 degree", "[experiments][slide]") {
  CaseSpec spec = load_case(std::string(REPOSE_SOURCE_DIR) + "/cases/experiments/slide_four_spheres.toml");
  TiltResult r = run_tilt(spec);
  CHECK(std::abs(r.onset_angle_deg - std::atan(0.34) * 180 / kPi) < 1.0);
  CHECK(r.tan_alpha == Approx(0.34).margin(0.02));
  CHECK(!r.wall_forces.rows.empty());
}

TEST_CASE("inclined rolling: the distance on the floor matches the constant-rolling-torque theory within 3 %",
          "[experiments][roll]") {
  CaseBuilder b;
  int grain = b.material(1000, 1e6, 0.3);
  int steel = b.material(7800, 8e10, 0.3);
  const double R = 0.05, mu_r = 0.05, beta = 10 * kPi / 180, S = 0.26, g = 9.81;
  b.interaction(grain, steel, 0.5, 0.5, mu_r);
  b.spec.gravity = {0, 0, -g};
  b.spec.time.rayleigh_fraction = 0.2;
  b.sphere({0, 0, 0}, R, grain);
  b.plane({0, 0, 0}, {0, 0, 1}, steel);
  b.spec.experiment.type = "roll";
  b.spec.experiment.max_time = 8;
  RollResult r = run_roll(b.spec);
  // Theory for a solid sphere under a constant rolling torque mu_r N R:
  // - rolling down the incline until it touches the floor (contact point S - R tan(beta/2) down
  //   the slope): (7/10) v1^2 = g s (sin(beta) - mu_r cos(beta));
  // - on touching the floor the vertical velocity is lost and friction brings the sphere back to
  //   rolling, keeping the angular momentum about the contact point: v2 = v1 (5 cos(beta) + 2) / 7;
  // - then (7/10) v2^2 = mu_r g L' on the floor; the centre starts R tan(beta/2) past the foot.
  double s = S - R * std::tan(beta / 2);
  double v1 = std::sqrt(10.0 / 7.0 * g * s * (std::sin(beta) - mu_r * std::cos(beta)));
  double v2 = v1 * (5 * std::cos(beta) + 2) / 7;
  double L = R * std::tan(beta / 2) + 7 * v2 * v2 / (10 * g * mu_r);
  INFO("L = " << r.rolling_distance << " m, theory " << L << " m; mu_r from the cabbage study's formula " << r.mu_r);
  // Not in the theory: the soft contact's bounce at the floor and the rolling torque during the
  // short slip there (about 2 % of L in this configuration).
  CHECK(r.rolling_distance == Approx(L).epsilon(0.03));
  // The cabbage study's formula ignores the loss at the foot: it reads mu_r a few % high.
  CHECK(r.mu_r == Approx(mu_r).epsilon(0.08));
}

TEST_CASE("random_orientation: a roll's seed is a replicate, as --replicates draws it", "[experiments][roll][clump]") {
  // A calibration varies only the seed between its replicates, so the orientation must follow it.
  const std::string path = std::string(REPOSE_SOURCE_DIR) + "/cases/experiments/roll_cabbage.toml";
  auto seeded = [&](int seed) {
    return load_case(path, {{"experiment.random_orientation", "true"}, {"simulation.seed", std::to_string(seed)}});
  };
  double l2 = run_roll(seeded(2)).rolling_distance, l3 = run_roll(seeded(3)).rolling_distance;
  INFO("seed 2: L = " << l2 << " m, seed 3: L = " << l3 << " m");
  CHECK(l2 != l3);                                            // another orientation, another roll
  CHECK(run_roll(seeded(2)).rolling_distance == l2);         // same seed, same bytes
  ExperimentRun two;
  two.replicates = 2;                                         // seeds 2 and 3 from base seed 2
  two.strict = false;
  ExperimentOutcome o = roll_experiment().run(seeded(2), two);
  CHECK(o.values.at("rolling_distance") == Approx((l2 + l3) / 2).epsilon(1e-12));
}
