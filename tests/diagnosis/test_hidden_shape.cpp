// Hidden `shape` (issue 5): the truth drops an elongated body (a seven-sphere chain of the
// cabbage's volume, aspect ratio drawn in [1.5, 2.5]) that lands at a random orientation, so its
// rebound scatters between replicates by ~20-30 mm and falls on average. The data give sigma
// (1 mm, the camera's error), so the scatter itself is data: diagnose must name `shape` from it.
// Three heights, eight replicates each (the scatter's signature needs replicates more than
// conditions; three heights keep leave-one-out possible and the test near a minute).
#include <algorithm>

#include "hidden_effect_support.h"

using namespace repose;
using namespace repose::hidden;

static const std::vector<double> kShapeHeights = {0.30, 0.40, 0.50};

static SyntheticTruth shape_truth(uint64_t seed) {
  SyntheticTruth truth;
  truth.case_path = case_path("cabbage_drop");
  truth.extension = "shape";
  truth.extension_params = {draw(seed, 1.5, 2.5)};
  truth.heights = kShapeHeights;
  truth.replicates = 8;
  truth.noise = 0.001;
  truth.write_sigma = true;
  truth.seed = seed;
  return truth;
}

TEST_CASE("hidden shape is named from the replicate scatter (cabbage, sigma given)", "[diagnosis][hidden]") {
  SyntheticTruth truth = shape_truth(21);
  Diagnosis d = diagnose_hidden("shape", truth);
  INFO("truth: aspect_ratio " << truth.extension_params[0] << "\n" << summary(d));
  CHECK(d.verdict == "effect");
  REQUIRE(d.cause.size() == 1);
  CHECK(d.cause[0] == "shape");
  // Held-out error of (mean, SD) together: the baseline predicts an SD of 1 mm against ~25 mm
  // measured, a model with the right shape misses only by the sampling error of eight replicates
  // (~35 % of the SD) and of the means: measured gains 45-60 %, so 30 % is a clear threshold.
  CHECK(d.gain_percent > 30);
  // The aspect ratio is named but not pinned: any chain from a ~ 1.3 up scatters by ~25 mm, and
  // the mean trades a against the restitution (measured with `synth-data` + `diagnose`: fitted
  // 2.35, 2.52, 1.46 for hidden 1.6, 2.0, 2.4). What the data do show is an elongated body.
  CHECK(candidate(d, "shape").params.back() > 1.2);
}

TEST_CASE("shape data without a sigma column: shape is not tested and the diagnosis says why",
          "[diagnosis][hidden]") {
  SyntheticTruth truth = shape_truth(22);
  truth.write_sigma = false;
  Diagnosis d = diagnose_hidden("shape_no_sigma", truth);
  INFO("truth: aspect_ratio " << truth.extension_params[0] << "\n" << summary(d));
  const ModelResult& shape = candidate(d, "shape");
  CHECK_FALSE(shape.tested);
  CHECK(shape.untested_reason.find("sigma") != std::string::npos);
  // The scatter, taken as noise, hides the mean's change: no other candidate may claim it.
  CHECK(d.verdict == "adequate");
}

TEST_CASE("sigma given, no hidden effect: adequate, shape fitted and rejected (no false alarm)",
          "[diagnosis][hidden]") {
  SyntheticTruth truth;
  truth.case_path = case_path("cabbage_drop");
  truth.restitution = draw(23, 0.38, 0.48);
  truth.heights = kShapeHeights;
  truth.replicates = 8;
  truth.write_sigma = true;
  truth.seed = 23;
  Diagnosis d = diagnose_hidden("none_sigma", truth);
  INFO("truth: baseline, restitution " << *truth.restitution << "\n" << summary(d));
  CHECK(d.verdict == "adequate");
  CHECK(candidate(d, "shape").tested);
  CHECK_FALSE(candidate(d, "shape").significant);
  CHECK(d.baseline.params.at(0) == Approx(*truth.restitution).margin(0.01));
}

TEST_CASE("sigma given, hidden restitution_velocity: still named, shape fitted and rejected",
          "[diagnosis][hidden]") {
  // The scatter's deviance must not turn a deterministic effect into a false `shape`: the truth
  // is the cabbage test of test_hidden_effects.cpp with the camera error given as sigma.
  SyntheticTruth truth;
  truth.case_path = case_path("cabbage_drop");
  truth.restitution = 0.9;
  truth.extension = "restitution_velocity";
  truth.extension_params = {draw(24, 1.2e-3, 2.0e-3, true)};
  truth.heights = {0.30, 0.35, 0.40, 0.45, 0.50};
  truth.write_sigma = true;
  truth.seed = 24;
  Diagnosis d = diagnose_hidden("restitution_velocity_sigma", truth);
  INFO("truth: viscoelastic_time " << truth.extension_params[0] << " s\n" << summary(d));
  CHECK(d.verdict == "effect");
  REQUIRE(d.cause.size() == 1);
  CHECK(d.cause[0] == "restitution_velocity");
  CHECK(d.gain_percent > 25);
  CHECK(candidate(d, "shape").tested);
  CHECK_FALSE(candidate(d, "shape").significant);
}
