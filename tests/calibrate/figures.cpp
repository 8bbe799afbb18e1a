// Every figure of a campaign report, read back from what its chart recorded: no repeated tick
// label, every legend entry drawn with its own mark, no legend over the data, every run shown.
#include <catch2/catch.hpp>

#include <filesystem>

#include "calibrate/adaptive_loop.h"
#include "calibrate/campaign.h"
#include "calibrate/design_analysis.h"
#include "calibrate/design_runs.h"
#include "calibrate/report_figures.h"
#include "calibrate_support.h"
#include "function_runs.h"
#include "plot/chart.h"

using namespace repose;
using namespace repose::calibrate;

namespace {

// What every chart must satisfy.
void check_chart(const std::string& path, bool box_legend) {
  INFO(path);
  const ChartRecord r = Chart::recorded(path);
  for (const auto* ticks : {&r.x_ticks, &r.y_ticks, &r.bar_ticks})
    for (size_t i = 1; i < ticks->size(); ++i) CHECK((*ticks)[i] != (*ticks)[i - 1]);
  CHECK_FALSE(r.title.empty());
  CHECK_FALSE(r.x_label.empty());
  CHECK_FALSE(r.y_label.empty());
  REQUIRE_FALSE(r.legend.empty());
  for (const auto& e : r.legend) {
    INFO("legend entry '" << e.label << "'");
    CHECK(r.points_of(e.colour, e.mark) > 0);
  }
  if (box_legend) CHECK_FALSE(r.legend_covers_data);
}

bool whole_numbers(const std::vector<std::string>& ticks) {
  for (const auto& t : ticks)
    if (t.find_first_of(".e") != std::string::npos) return false;
  return !ticks.empty();
}

double tick_value(const std::string& t) { return std::stod(t); }

}  // namespace

TEST_CASE("the design figures show every series they name, with whole-number run axes") {
  Chart::keep_records();
  const std::string dir = test::scratch_dir("figures_design");
  // x1 sets the response, x2 does nothing (as G in the drop test): a flat calibration curve.
  CampaignPlan plan = test::function_plan(2, 10.5, 0.05, 0.01);
  plan.design.type = "ccd";
  plan.design.centre = 3;
  plan.design.model = "quadratic";
  plan.verification_runs = 3;
  test::FunctionRuns runs(plan, [](const Eigen::VectorXd& c, int) { return 10 + 2 * c[0]; }, 0.0, 1);
  runs.run(design_runs(plan), "design");
  CalibrationResult res = analyse_design(plan, runs);
  verify_result(plan, runs, replicate_runs(plan, "verify", res.chosen, 0, 3), res);
  REQUIRE(res.target_reached);
  std::vector<Figure> figures = write_figures(plan, res, dir);
  std::vector<std::string> names;
  for (const auto& f : figures) names.push_back(f.file);
  CHECK(names == std::vector<std::string>{"contour.png", "main_effects.png", "calibration_x1.png", "calibration_x2.png",
                                          "predicted_vs_simulated.png", "posterior.png", "verification.png"});
  check_chart(dir + "/contour.png", false);
  check_chart(dir + "/main_effects.png", true);
  check_chart(dir + "/calibration_x1.png", true);
  check_chart(dir + "/calibration_x2.png", true);
  check_chart(dir + "/predicted_vs_simulated.png", true);
  check_chart(dir + "/posterior.png", false);
  check_chart(dir + "/verification.png", true);
  // The contour shows all 11 runs as dots and the chosen point as a cross.
  const ChartRecord contour = Chart::recorded(dir + "/contour.png");
  CHECK(contour.points_of(colours::black, Mark::Dot) == 11);
  CHECK(contour.points_of(colours::red, Mark::Cross) == 1);
  // The measured value's line has a legend entry on the main effects.
  const ChartRecord effects = Chart::recorded(dir + "/main_effects.png");
  CHECK(effects.legend.size() == 3);
  CHECK(effects.legend.back().colour == colours::black);
  // The flat curve of x2: its axis spans well beyond the tolerance band (no plot of one colour).
  const ChartRecord flat = Chart::recorded(dir + "/calibration_x2.png");
  CHECK(tick_value(flat.y_ticks.back()) - tick_value(flat.y_ticks.front()) >= 3 * plan.responses[0].absolute_tolerance());
  // Runs are counted in whole numbers.
  CHECK(whole_numbers(Chart::recorded(dir + "/verification.png").x_ticks));
  CHECK(Chart::recorded(dir + "/verification.png").points_of(colours::red, Mark::Dot) == 3);
}

TEST_CASE("the loop's convergence shows every run and the line between start and proposals") {
  Chart::keep_records();
  const std::string dir = test::scratch_dir("figures_loop");
  CampaignPlan plan = test::function_plan(1, 10.5, 0.1, 0.01);
  plan.mode = CampaignMode::adaptive;
  plan.adaptive.seed_per_run = true;
  plan.adaptive.pilot = 3;
  plan.adaptive.initial = 3;
  plan.adaptive.budget = 8;
  plan.verification_runs = 2;
  test::FunctionRuns runs(plan, [](const Eigen::VectorXd& c, int) { return 10 + 2 * c[0]; }, 0.3, 2);
  AdaptiveOutcome loop = run_adaptive(plan, runs, true);
  REQUIRE(int(loop.steps.size()) > loop.initial);
  write_convergence_figure(plan, loop, dir);
  check_chart(dir + "/convergence.png", true);
  const ChartRecord r = Chart::recorded(dir + "/convergence.png");
  CHECK(r.points_of(colours::black, Mark::Dot) == int(loop.steps.size()));
  CHECK(r.points_of(colours::grey, Mark::Line) > 0);
  CHECK(whole_numbers(r.x_ticks));
  write_figures(plan, loop.result, dir);
  check_chart(dir + "/posterior.png", true);  // one factor: its density, a box legend
}

TEST_CASE("the convergence legend finds room when noisy runs fill every corner") {
  // Errors alternating between 1 % and 50 %, from the first run to the last: the cylinder
  // campaign's figure had data in all four corners and its legend covered a run.
  Chart::keep_records();
  const std::string dir = test::scratch_dir("figures_loop_corners");
  CampaignPlan plan = test::function_plan(1, 10.5, 0.1, 0.01);
  AdaptiveOutcome loop;
  loop.initial = 3;
  for (int i = 0; i < 14; ++i) {
    LoopStep step;
    step.relative_error = i % 2 ? 0.5 : -0.01;
    loop.steps.push_back(step);
  }
  write_convergence_figure(plan, loop, dir);
  check_chart(dir + "/convergence.png", true);
  CHECK_FALSE(Chart::recorded(dir + "/convergence.png").legend_covers_data);
}

TEST_CASE("the steepest-ascent figure shows each point's mean, its runs and the chosen point") {
  Chart::keep_records();
  const std::string dir = test::scratch_dir("figures_path");
  CampaignPlan plan = test::function_plan(2, 12.0, 0.1, 0.02);
  plan.design.type = "path";
  plan.design.levels = 6;
  plan.design.replicates = 3;
  plan.design.path_from = {0.0, 0.0};
  plan.design.path_to = {1.0, 1.0};
  test::FunctionRuns runs(plan, [](const Eigen::VectorXd& c, int) { return 10 + 2 * c[0] + 2 * c[1]; }, 0.2, 3);
  runs.run(design_runs(plan), "design");
  CalibrationResult res = analyse_design(plan, runs);
  REQUIRE(res.path.size() == 6);
  write_figures(plan, res, dir);
  check_chart(dir + "/path.png", true);
  const ChartRecord r = Chart::recorded(dir + "/path.png");
  CHECK(r.points_of(colours::grey, Mark::Dot) == 18);
  CHECK(r.points_of(colours::blue, Mark::Square) == 6);
  CHECK(whole_numbers(r.x_ticks));
}
