// Hidden effects in the cheap tilt and roll tests (issue 5): measured data simulated with a truth
// model, diagnosed from the CSV alone.
// - Roll: a light foam ball (cases/diagnosis/foam_ball_roll.toml) released S = 0.2-1.0 m up a
//   10 deg incline, 5 replicates of L with 10 mm noise (a tape measure on 0.5-2.4 m), so a mean
//   carries 4.5 mm. Hidden air drag shortens L by 4-17 % (20-400 mm) growing with S, which a
//   refitted rolling friction cannot follow: the drag model must win and gain 50 % of held-out
//   error (measured 84 % at C_d 0.4), far from what noise alone gives a one-parameter rival.
// - Slide: the cabbage study's four bonded cabbages at densities 250-1200 kg/m^3 (lighter and heavier
//   bodies of the same shape), 5 replicate angles with 0.5 deg noise. Cohesion (moisture) pulls
//   each contact together by k pi R* dn and friction grips on the raised repulsion, so the body
//   slides later, by more the lighter it is (the pull grows as dn ~ W^(2/3), the weight as W): a
//   friction refitted alone cannot follow the trend. Without it the baseline is adequate, the
//   friction recovered, and the candidates no static tilt responds to are untested with the reason.
#include <fstream>

#include "hidden_effect_support.h"

using namespace repose;
using namespace repose::hidden;

static const std::vector<double> kSlopeDistances = {0.2, 0.4, 0.6, 0.8, 1.0};

static SyntheticTruth foam_ball_roll(uint64_t seed) {
  SyntheticTruth truth;
  truth.case_path = case_path("foam_ball_roll");
  truth.plate_friction = draw(seed, 0.035, 0.065);  // the ball's rolling friction on steel
  truth.heights = kSlopeDistances;                  // experiment.slope_distance, m
  truth.noise = 0.01;
  truth.seed = seed;
  return truth;
}

TEST_CASE("hidden air_drag is named from rolling distances (foam ball)", "[diagnosis][hidden][roll]") {
  SyntheticTruth truth = foam_ball_roll(31);
  truth.extension = "air_drag";
  truth.extension_params = {draw(32, 0.25, 0.8, true)};
  Diagnosis d = diagnose_hidden("roll_air_drag", truth);
  INFO("truth: rolling friction " << *truth.plate_friction << ", drag coefficient " << truth.extension_params[0]
                                  << "\n" << summary(d));
  // The held-out error is measured on the measure the data give (issue 27: every measure, each
  // reported; once the "primary" measure alone).
  REQUIRE(d.baseline.heldout_by_measure.size() == 1);
  CHECK(d.baseline.heldout_by_measure[0].measure == "roll_distance");
  CHECK(d.verdict == "effect");
  REQUIRE(d.cause.size() == 1);
  CHECK(d.cause[0] == "air_drag");
  CHECK(d.gain_percent > 50);
  const ModelResult& drag = candidate(d, "air_drag");
  // Both parameters recovered: the friction sets L at small S, the drag its bend at large S
  // (tolerances: a few standard errors of each, from the 4.5 mm means).
  CHECK(drag.params.at(0) == Approx(*truth.plate_friction).epsilon(0.05));
  CHECK(drag.params.at(1) == Approx(truth.extension_params[0]).epsilon(0.25));
}

TEST_CASE("rolling distances without a hidden effect: the baseline is adequate", "[diagnosis][hidden][roll]") {
  SyntheticTruth truth = foam_ball_roll(33);
  Diagnosis d = diagnose_hidden("roll_none", truth);
  INFO("truth: rolling friction " << *truth.plate_friction << "\n" << summary(d));
  CHECK(d.verdict == "adequate");
  CHECK(d.cause.empty());
  // 25 values of L with 10 mm noise pin a friction that sets L ~ S / mu_r to well under 1 %.
  CHECK(d.baseline.params.at(0) == Approx(*truth.plate_friction).epsilon(0.01));
  CHECK(candidate(d, "air_drag").tested);
}

// The four bonded cabbages at four densities; the clump's template travels with the case.
static SyntheticTruth four_cabbages_slide(const std::string& name, uint64_t seed) {
  namespace fs = std::filesystem;
  SyntheticTruth truth;
  truth.case_path = std::string(REPOSE_SOURCE_DIR) + "/cases/experiments/slide_four_spheres.toml";
  truth.plate_friction = draw(seed, 0.3, 0.5);
  truth.condition_key = "material.cabbage.density";
  truth.heights = {250, 400, 600, 850, 1200};  // kg/m^3: the same bodies, lighter and heavier
  truth.angle_noise = 0.5;
  truth.seed = seed;
  fs::path dir = fs::temp_directory_path() / ("repose_hidden_" + name);
  fs::create_directories(dir);
  fs::copy_file(std::string(REPOSE_SOURCE_DIR) + "/cases/experiments/four_spheres.csv", dir / "four_spheres.csv",
                fs::copy_options::overwrite_existing);
  return truth;
}

TEST_CASE("slide angles without a hidden effect: the friction is fitted, the baseline adequate",
          "[diagnosis][hidden][slide]") {
  SyntheticTruth truth = four_cabbages_slide("slide", 34);
  Diagnosis d = diagnose_hidden("slide", truth);
  INFO("truth: static friction " << *truth.plate_friction << "\n" << summary(d));
  REQUIRE(d.baseline.heldout_by_measure.size() == 1);
  CHECK(d.baseline.heldout_by_measure[0].measure == "slide_angle");
  CHECK(d.verdict == "adequate");
  // 20 angles with 0.5 deg noise: tan(alpha) to ~0.002 (0.5 deg / sqrt(20) in radians x sec^2).
  CHECK(d.baseline.params.at(0) == Approx(*truth.plate_friction).margin(0.01));
  for (const auto& c : d.candidates) {
    INFO(c.id);
    if (c.id == "cohesion") {
      CHECK(c.tested);  // fitted and rejected
      continue;
    }
    CHECK_FALSE(c.tested);
    CHECK(c.untested_reason.find("none of the measured quantities") != std::string::npos);
  }
}

TEST_CASE("hidden cohesion is named from slide angles at five densities", "[diagnosis][hidden][slide]") {
  // k 1e4-2e4 J/m^3 raises the angle by 1.5-3 deg at 300 kg/m^3 and half that at 1200; the
  // means carry 0.22 deg. Measured at 4 densities: 1e4 -> fitted 8,750 (friction 0.408 for 0.4),
  // held-out 0.56 -> 0.07 deg (88 %); 2e4 -> 18,800 (94 %); but this draw gained only 25 % there,
  // an end density predicted from three. At 5 densities its three noise draws gain 60-86 %:
  // threshold 40 % (a wrong cause gains nothing).
  SyntheticTruth truth = four_cabbages_slide("slide_cohesion", 35);
  truth.extension = "cohesion";
  truth.extension_params = {draw(36, 1e4, 2e4, true)};
  Diagnosis d = diagnose_hidden("slide_cohesion", truth);
  INFO("truth: static friction " << *truth.plate_friction << ", cohesion " << truth.extension_params[0] << "\n"
                                 << summary(d));
  CHECK(d.verdict == "effect");
  REQUIRE(d.cause.size() == 1);
  CHECK(d.cause[0] == "cohesion");
  CHECK(d.gain_percent > 40);
  const ModelResult& c = candidate(d, "cohesion");
  CHECK(c.params.at(0) == Approx(*truth.plate_friction).margin(0.02));
  CHECK(c.params.at(1) == Approx(truth.extension_params[0]).epsilon(0.25));
}

TEST_CASE("a measure the experiment does not report is named with its line", "[diagnosis][roll]") {
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / "repose_roll_bad_measure";
  fs::create_directories(dir);
  fs::copy_file(case_path("foam_ball_roll"), dir / "foam_ball_roll.toml", fs::copy_options::overwrite_existing);
  std::string csv = (dir / "data.csv").string();
  {
    std::ofstream out(csv);
    out << "case,set:experiment.slope_distance,measure,value,replicate\n"
           "foam_ball_roll.toml,0.2,roll_distance,0.47,1\n"
           "foam_ball_roll.toml,0.2,roll_distance,0.48,2\n"
           "foam_ball_roll.toml,0.2,slide_angle,20,1\n"
           "foam_ball_roll.toml,0.2,slide_angle,21,2\n";
  }
  DiagnoseOptions options;
  options.progress = false;
  try {
    diagnose(group_observations(read_measured_data(csv)), options);
    FAIL("no error");
  } catch (const DataError& e) {
    std::string what = e.what();
    CHECK(what.find("data.csv:4") != std::string::npos);
    CHECK(what.find("'slide_angle'") != std::string::npos);
    CHECK(what.find("roll: roll_distance") != std::string::npos);
  }
}
