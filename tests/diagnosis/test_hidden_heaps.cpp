// Hidden effects in heaps (cases/diagnosis/slot_heap.toml, the angle of repose and the bed height
// at three fill counts). A heap costs ~1000 drops, and a diagnosis that refits the baseline's
// friction next to each candidate's parameter runs ~2,000 heaps (8 minutes on two cores; the worked
// examples in docs/diagnosis/ do that). The ctest takes the calibrated baseline as given, as a
// user with a calibrated model does (`diagnose --params`): the truth is that baseline plus one
// extension of random strength; only the extension's own parameter is fitted.
#include "hidden_effect_support.h"

using namespace repose;
using namespace repose::hidden;

TEST_CASE("hidden rolling_epsd is named from heaps, the calibrated friction given", "[diagnosis][hidden][heap]") {
  // EPSD with spinning friction = rolling friction lowers the slot heap's angle by ~4 deg and
  // leaves the bed height within ~1 mm (measured over 6 fills per count; replicate SD 1.5-2.5 deg).
  // Six replicate heaps per count give means to ~0.8-1.2 deg, so the baseline misses by 3-5 SE.
  // 150-250 grains: since spinning friction's limiter counts touching contacts (it counted list
  // entries), EPSD heaps of 120 grains scatter over 16.8-29.5 deg (fill seeds 1-8), and with
  // 120-200 grains this draw came out ambiguous (F p = 0.008, held-out error 25 % worse). With
  // 150-250 it fitted 0.45, chi^2 33.4 -> 9.3 on fresh fills (F p = 0.0002), held-out angle
  // 2.56 -> 1.33 deg (48 % less), bed 1.09 -> 0.45 mm; draws 22, 23 and 24 pass as well. An angle
  // gain above 30 % leaves room for the simulated replicates' own scatter and stays above what a
  // wrong cause reaches (the baseline itself: 0 %).
  SyntheticTruth truth;
  truth.case_path = case_path("slot_heap");
  truth.extension = "rolling_epsd";
  truth.extension_params = {draw(21, 0.2, 0.6)};
  truth.heights = {150, 200, 250};
  truth.replicates = 6;
  truth.angle_noise = 0.5;
  truth.noise = 5e-4;
  truth.seed = 21;
  DiagnoseOptions options;
  options.given = {{"interaction.grain/grain.static_friction", "0.5"}};  // the case's: calibrated
  options.fit_baseline = false;
  options.candidates = {"rolling_epsd"};
  // Six simulated heaps per count: with three, the fit's damping is chosen by the fills' luck
  // (heaps scatter by ~3 deg, EPSD's effect is ~4 deg), and scored on fresh fills it no longer
  // beats the baseline (diagnose_stages.h; measured with list-entry spinning friction: fitted
  // 0.80 for a hidden 0.31, where fills 4-11 at 0.31 stood at 23.1 and 22.5 deg at 120 and 200
  // grains as the data did, and at 0.8 at 25.3 and 25.1, near the baseline's 26.7).
  options.simulated_replicates = 6;
  Diagnosis d = diagnose_hidden("rolling_epsd_heap", truth, nullptr, options);
  INFO("truth: rolling_damping " << truth.extension_params[0] << "\n" << summary(d));
  CHECK(d.verdict == "effect");
  REQUIRE(d.cause.size() == 1);
  CHECK(d.cause[0] == "rolling_epsd");
  // The gain where the effect shows, the angle (issue 27: once the only measure the gain was
  // taken on, now reported per measure): measured 2.56 -> 1.33 deg (48 %). Over both measures, in
  // standard errors, 55 %; it must be a gain.
  const ModelResult& epsd = candidate(d, "rolling_epsd");
  REQUIRE(epsd.heldout_by_measure.size() == 2);
  REQUIRE(epsd.heldout_by_measure[0].measure == "repose_angle");
  CHECK(epsd.heldout_by_measure[0].rms < 0.7 * d.baseline.heldout_by_measure[0].rms);
  CHECK(d.gain_percent > 0);
  CHECK(d.heldout_error_extended < d.heldout_error_baseline);
}

TEST_CASE("hidden size_spread is named from bed heights alone, the calibrated friction given",
          "[diagnosis][hidden][heap]") {
  // A size spread packs the same count of grains into a higher bed (their mean volume grows as
  // (1 + s^2)): at s = 0.35, +5-9 mm at 150-250 grains where replicate beds scatter by ~1-4 mm,
  // while the angle moves less than its 2-4 deg scatter. So the data here are bed heights only,
  // and the diagnosis simulates the bed alone (fill and settle to the lift, a third of a heap).
  // EPSD, the rival, moves the bed by ~1 mm. Measured with this draw (0.378): fitted 0.398,
  // chi^2 82.6 -> 4.9 on 8 fresh beds, EPSD refitted to it misses by chi^2 43, held-out bed
  // 8.64 -> 1.84 mm (79 % less). Threshold 30 % as for EPSD; the fitted spread within 0.1 (the
  // fit's range is 0-0.4).
  SyntheticTruth truth;
  truth.case_path = case_path("slot_heap");
  truth.extension = "size_spread";
  truth.extension_params = {draw(22, 0.25, 0.4)};
  // Up to 200 grains: at 250 a spread near the fit's 0.4 no longer fits the fill box.
  truth.heights = {120, 160, 200};
  truth.replicates = 6;
  truth.noise = 5e-4;
  truth.bed_height_only = true;
  truth.seed = 22;
  DiagnoseOptions options;
  options.given = {{"interaction.grain/grain.static_friction", "0.5"}};
  options.fit_baseline = false;
  options.candidates = {"size_spread", "rolling_epsd"};
  options.simulated_replicates = 3;
  Diagnosis d = diagnose_hidden("size_spread_bed", truth, nullptr, options);
  INFO("truth: size_spread " << truth.extension_params[0] << "\n" << summary(d));
  CHECK(d.verdict == "effect");
  REQUIRE(d.cause.size() == 1);
  CHECK(d.cause[0] == "size_spread");
  CHECK(d.gain_percent > 30);
  const ModelResult& spread = candidate(d, "size_spread");
  REQUIRE(spread.tested);
  CHECK(spread.params.back() == Approx(truth.extension_params[0]).margin(0.1));
}
