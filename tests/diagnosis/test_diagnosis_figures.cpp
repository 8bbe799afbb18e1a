// The diagnosis report's figures, read back from their charts' records (tests/figure_checks.h):
// every series drawn and in the legend with its own mark, distinct tick labels, no data hidden
// under the legend, lengths in millimetres. The fits are given (a baseline 5 % low, a winner on
// the data), so nothing is simulated.
#include <catch2/catch.hpp>

#include <filesystem>

#include "../figure_checks.h"
#include "diagnosis/diagnosis_report.h"
#include "diagnosis/observations.h"
#include "diagnosis/measured_data.h"

using namespace repose;

TEST_CASE("the diagnosis figures show every series, in millimetres, with distinct ticks", "[diagnosis][figures]") {
  Observations obs =
      group_observations(read_measured_data(std::string(REPOSE_SOURCE_DIR) + "/cases/diagnosis/cotton_stalk_data.csv"));
  Diagnosis d;
  d.verdict = "effect";
  d.cause = {"restitution_velocity"};
  d.baseline.id = "baseline";
  ModelResult winner;
  winner.id = "restitution_velocity";
  for (const auto& g : obs.groups) {
    d.baseline.predicted.push_back(0.95 * g.mean);
    winner.predicted.push_back(g.mean + 0.1 * g.sd);
  }
  d.candidates = {winner};
  std::filesystem::path dir = std::filesystem::temp_directory_path() / "repose_test_diagnosis_figures";
  std::filesystem::remove_all(dir);
  Chart::keep_records();
  write_diagnosis(obs, d, dir.string());
  auto figure = [&](const std::string& file) { return Chart::recorded((dir / file).string()); };

  ChartRecord residuals = figure("residuals_rebound_height_vs_drop_height.png");
  test::check_figure(residuals, {"baseline", "restitution_velocity"});
  CHECK(residuals.y_label == "rebound_height (mm) residual");
  // The baseline's residuals are 5 % of rebounds of 20-70 mm: millimetres, not metres.
  double largest = 0;
  for (const auto& t : residuals.y_ticks) largest = std::max(largest, std::abs(std::stod(t)));
  CHECK(largest > 0.5);

  ChartRecord scatter = figure("measured_vs_simulated_rebound_height.png");
  test::check_figure(scatter, {"baseline", "restitution_velocity", "measured = simulated"});
  CHECK(scatter.x_label == "simulated rebound_height (mm)");
  int means = 0;  // one per drop height
  for (const auto& g : obs.groups) means += g.measure == "rebound_height";
  CHECK(scatter.points_of({200, 40, 40}, Mark::Square) == means);

  test::check_figure(figure("residuals_height_vs_t.png"), {"baseline", "restitution_velocity"});
  ChartRecord series = figure("series_height.png");
  test::check_figure(series, {"measured", "baseline", "restitution_velocity"});
  CHECK(series.y_label == "height (mm)");
  std::filesystem::remove_all(dir);
}
