// Tests that hide an effect (issue 5): measured data are simulated with a truth model, the
// calibrated baseline plus one extension drawn with a random strength (seeded, so CI sees the
// same draw), at five drop heights with five replicates and Gaussian replicate noise of 1 mm per
// rebound height (and 1 mm per tracked height of a trajectory). `diagnose` sees only the CSV.
// It must name the hidden cause and gain at least 25 % of held-out error: with 1 mm noise the
// means carry 0.45 mm, the hidden effects move rebound heights by 2-6 mm across the heights, so
// a model that has found the cause predicts a held-out height at about the noise of a mean
// (measured gains 40-70 %), while 25 % stays clear of what a wrong cause reaches.
#include <algorithm>

#include "hidden_effect_support.h"

using namespace repose;
using namespace repose::hidden;

static const std::vector<double> kHeights = {0.30, 0.35, 0.40, 0.45, 0.50};

TEST_CASE("no hidden effect: the baseline is adequate (no false alarm)", "[diagnosis][hidden]") {
  SyntheticTruth truth;
  truth.case_path = case_path("cabbage_drop");
  truth.restitution = draw(11, 0.38, 0.48);
  truth.heights = kHeights;
  truth.seed = 11;
  Diagnosis d = diagnose_hidden("none", truth);
  INFO("truth: baseline, restitution " << *truth.restitution << "\n" << summary(d));
  CHECK(d.verdict == "adequate");
  CHECK(d.cause.empty());
  CHECK(d.baseline.params.at(0) == Approx(*truth.restitution).margin(0.01));
}

TEST_CASE("hidden restitution_velocity is named from drop heights (cabbage)", "[diagnosis][hidden]") {
  SyntheticTruth truth;
  truth.case_path = case_path("cabbage_drop");
  truth.restitution = 0.9;  // a lively contact whose damping is mostly viscoelastic
  truth.extension = "restitution_velocity";
  truth.extension_params = {draw(12, 1.2e-3, 2.0e-3, true)};
  truth.heights = kHeights;
  truth.seed = 12;
  Diagnosis d = diagnose_hidden("restitution_velocity", truth);
  INFO("truth: viscoelastic_time " << truth.extension_params[0] << " s\n" << summary(d));
  CHECK(d.verdict == "effect");
  REQUIRE(d.cause.size() == 1);
  CHECK(d.cause[0] == "restitution_velocity");
  CHECK(d.gain_percent > 25);
  CHECK(d.heldout_error_extended < d.heldout_error_baseline);
}

TEST_CASE("hidden cohesion is named from drop heights (cabbage)", "[diagnosis][hidden]") {
  SyntheticTruth truth;
  truth.case_path = case_path("cabbage_drop");
  truth.extension = "cohesion";
  // EDEM's linear cohesion is conservative: in a drop it acts only through the damping it deepens,
  // and below ~1e5 J/m^3 a refitted restitution absorbs it (measured: 5e4 gives F-test p = 0.035).
  // Hidden here above that.
  truth.extension_params = {draw(13, 1.2e5, 2.5e5, true)};
  truth.heights = kHeights;
  truth.seed = 13;
  Diagnosis d = diagnose_hidden("cohesion", truth);
  INFO("truth: cohesion_energy_density " << truth.extension_params[0] << " J/m^3\n" << summary(d));
  CHECK(d.verdict == "effect");
  REQUIRE(d.cause.size() == 1);
  CHECK(d.cause[0] == "cohesion");
  CHECK(d.gain_percent > 25);
  // Drops name cohesion but pin its strength poorly (it trades off against the restitution:
  // fitted 1e4-7e4 for hidden 5e4-1.2e5 in the measurements of docs/diagnosis.md).
  CHECK(candidate(d, "cohesion").params.back() > 3e3);
}

TEST_CASE("hidden air_drag is named from heights with trajectories (foam ball)", "[diagnosis][hidden]") {
  SyntheticTruth truth;
  truth.case_path = case_path("foam_ball_drop");
  truth.extension = "air_drag";
  truth.extension_params = {draw(14, 0.4, 1.0)};
  truth.heights = kHeights;
  truth.series_dt = 0.01;
  truth.seed = 14;
  Diagnosis d = diagnose_hidden("air_drag", truth);
  INFO("truth: drag_coefficient " << truth.extension_params[0] << "\n" << summary(d));
  CHECK(d.verdict == "effect");
  REQUIRE(d.cause.size() == 1);
  CHECK(d.cause[0] == "air_drag");
  CHECK(d.gain_percent > 25);
  // Trajectories pin the drag coefficient: within 10 % (replicate noise alone gives ~2 %).
  CHECK(candidate(d, "air_drag").params.back() == Approx(truth.extension_params[0]).epsilon(0.1));
}

// The confounded case: a viscoelastic restitution hidden in a light ball's drops.
static SyntheticTruth confounded_truth() {
  SyntheticTruth truth;
  truth.case_path = case_path("foam_ball_drop");
  truth.restitution = 0.9;
  truth.extension = "restitution_velocity";
  // Strengths that are clear (chi^2 of the baseline 50-110) and that the heights' design still
  // cannot attribute (measured: air_drag mimics viscoelastic_time 3e-4 and 5e-4 s to chi^2 ~ 0.3).
  truth.extension_params = {draw(15, 3e-4, 5e-4, true)};
  truth.heights = kHeights;
  truth.seed = 15;
  return truth;
}

TEST_CASE("confounded: drop heights alone are ambiguous between air_drag and restitution_velocity",
          "[diagnosis][hidden]") {
  SyntheticTruth truth = confounded_truth();
  Diagnosis d = diagnose_hidden("confounded_heights", truth);
  INFO("truth: viscoelastic_time " << truth.extension_params[0] << " s\nheights only: " << summary(d));
  CHECK(d.verdict == "ambiguous");
  std::vector<std::string> cause = d.cause;
  std::sort(cause.begin(), cause.end());
  CHECK(cause == std::vector<std::string>{"air_drag", "restitution_velocity"});
  CHECK(d.separating_measurement.find("trajectory") != std::string::npos);
}

TEST_CASE("confounded: with the trajectory z(t) the right cause is named", "[diagnosis][hidden]") {
  SyntheticTruth truth = confounded_truth();
  truth.series_dt = 0.01;
  Diagnosis d = diagnose_hidden("confounded_series", truth);
  INFO("truth: viscoelastic_time " << truth.extension_params[0] << " s\nwith z(t): " << summary(d));
  CHECK(d.verdict == "effect");
  REQUIRE(d.cause.size() == 1);
  CHECK(d.cause[0] == "restitution_velocity");
  CHECK(d.gain_percent > 25);
}
