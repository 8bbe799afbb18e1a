// The verdict weighs all the evidence it computes (issue 27), checked on hidden effects in drops
// (seconds each): the gain measured on the measure that carries the effect, a modest signal that
// must not come out `adequate`, and a baseline fitted on a bound of its range said to be so.
#include <algorithm>
#include <sstream>

#include "hidden_effect_support.h"

using namespace repose;
using namespace repose::hidden;

static const std::vector<double> kHeights = {0.30, 0.35, 0.40, 0.45, 0.50};

namespace {

// A row's t column (the last), or a negative value for a scalar measure's row.
double row_time(const std::string& row) {
  std::string t = row.substr(row.rfind(',') + 1);
  return t.empty() ? -1 : std::stod(t);
}

// Cabbage drops at five heights, five replicates with 1 mm noise (test_hidden_effects.cpp's design).
SyntheticTruth cabbage_truth(uint64_t seed) {
  SyntheticTruth truth;
  truth.case_path = case_path("cabbage_drop");
  truth.heights = kHeights;
  truth.seed = seed;
  return truth;
}

DiagnoseOptions only(const std::string& candidate) {
  DiagnoseOptions options;
  options.candidates = {candidate};
  return options;
}

const MeasureError& measure_error(const ModelResult& r, const std::string& measure) {
  for (const auto& e : r.heldout_by_measure)
    if (e.measure == measure) return e;
  FAIL("no held-out error of " << measure << " for " << r.id);
  return r.heldout_by_measure.front();
}

}  // namespace

TEST_CASE("an effect in one of two measures: the gain is measured there, positive, and agrees with the verdict",
          "[diagnosis][hidden]") {
  // A viscoelastic restitution hidden in cabbage drops, measured as rebound heights and as the
  // camera's track of the fall only (t <= 0.2 s, before the first impact at 0.25 s): the track
  // shows nothing of the contact, every model predicts the same free fall. Once the gain was the
  // first scalar measure's alone; now each measure's is reported and the verdict's gain is over
  // both in standard errors. Measured (this draw): rebound_height 2.09 -> 0.20 mm (91 % less),
  // height 0.397 -> 0.397 mm (0 %), over both 3.14 -> 0.67 standard errors (79 %).
  SyntheticTruth truth = cabbage_truth(41);
  truth.restitution = 0.9;
  truth.extension = "restitution_velocity";
  truth.extension_params = {1.5e-3};
  truth.series_dt = 0.02;
  Diagnosis d = diagnose_hidden("evidence_two_measures", truth, nullptr, {},
                                [](const std::string& row) { return row_time(row) <= 0.2; });
  INFO(summary(d));
  CHECK(d.verdict == "effect");
  REQUIRE(d.cause.size() == 1);
  CHECK(d.cause[0] == "restitution_velocity");
  const ModelResult& named = candidate(d, "restitution_velocity");
  const MeasureError &rebound = measure_error(named, "rebound_height"), &track = measure_error(named, "height");
  double rebound_gain = 100 * (1 - rebound.sds / measure_error(d.baseline, "rebound_height").sds);
  double track_gain = 100 * (1 - track.sds / measure_error(d.baseline, "height").sds);
  // The effect's measure gains as in the single-measure tests (threshold 25 %); the fall's track
  // neither gains nor loses (the same free fall: within 1 %).
  CHECK(rebound_gain > 25);
  CHECK(std::abs(track_gain) < 1);
  CHECK(d.gain_percent > 25);
  CHECK(d.gain_percent == Approx(named.heldout_gain));
  std::string gain = d.statements.back();
  CHECK(gain.rfind("Gain: ", 0) == 0);
  CHECK(gain.find("rebound_height to") != std::string::npos);
}

TEST_CASE("a modest signal (F test p between 1 and 5 %, a large held-out gain) is never adequate",
          "[diagnosis][hidden]") {
  // Cohesion of 3e4 J/m^3 hidden in cabbage drops, below where drops name it at 1 % (docs:
  // 5e4 gives p = 0.035): the run B in miniature. Measured (this draw): F test p = 0.024,
  // 42 % less held-out error, cohesion's Akaike weight 0.88: `ambiguous`, cohesion named.
  SyntheticTruth truth = cabbage_truth(34);
  truth.extension = "cohesion";
  truth.extension_params = {3e4};
  Diagnosis d = diagnose_hidden("evidence_modest", truth, nullptr, only("cohesion"));
  INFO(summary(d));
  const ModelResult& cohesion = candidate(d, "cohesion");
  // The scenario's premise: a modest F test and a large held-out gain.
  CHECK(cohesion.p >= 0.01);
  CHECK(cohesion.p < 0.05);
  CHECK(cohesion.heldout_gain > kLargeGainPercent);
  CHECK(d.verdict != "adequate");
  CHECK((d.verdict == "effect" || d.verdict == "ambiguous"));
  REQUIRE_FALSE(d.cause.empty());
  CHECK(d.cause[0] == "cohesion");
  CHECK(d.confidence > 0.5);  // its Akaike weight against the baseline's
  for (const std::string& s : d.statements)
    if (s.rfind("cohesion:", 0) == 0) CHECK(s.find("no better") == std::string::npos);
}

TEST_CASE("a baseline fitted on a bound of its range is reported as evidence and as no calibration",
          "[diagnosis][hidden]") {
  // A restitution of 0.97 hidden in cabbage drops: the baseline's search range ends at 0.95.
  SyntheticTruth truth = cabbage_truth(43);
  truth.restitution = 0.97;
  Diagnosis d = diagnose_hidden("evidence_bound", truth, nullptr, only("air_drag"));
  INFO(summary(d));
  REQUIRE(d.baseline.at_bound.size() == 1);
  CHECK(d.baseline.at_bound[0].parameter == "restitution");
  CHECK(d.baseline.at_bound[0].upper);
  CHECK(d.baseline.params.at(0) == Approx(0.95).margin(0.005));
  bool said = std::any_of(d.statements.begin(), d.statements.end(), [](const std::string& s) {
    return s.find("The baseline's fit lies on a bound: restitution") != std::string::npos &&
           s.find("evidence for an effect") != std::string::npos && s.find("not a calibration") != std::string::npos;
  });
  CHECK(said);
}
