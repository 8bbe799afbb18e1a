// Design-Expert's screening and surface views (stats/effects.h, stats/design_figures.h) on the
// cotton-stalk study's Plackett-Burman screening (Table 3): standardised effects rank the factors
// as the study's Table 4 does, the t limits are the t table's, and each figure's record shows its
// series, distinct ticks and no data under the legend (tests/figure_checks.h).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <iterator>
#include <sstream>

#include "../figure_checks.h"
#include "stats/anova.h"
#include "stats/csv_table.h"
#include "stats/dataset.h"
#include "stats/design_figures.h"
#include "stats/effects.h"
#include "stats/report.h"

using namespace repose;
using namespace repose::stats;
namespace fs = std::filesystem;

namespace {

ResponseSurface cotton_screening() {
  Table t = read_csv(std::string(REPOSE_SOURCE_DIR) + "/tests/stats/data/cotton_table3_pb.csv");
  DataSet d = dataset_from_table(t, {"A", "B", "C", "D", "E", "F"}, "Y");
  return analyse(d.coded, d.y, build_model(ModelKind::linear, 6));
}

std::string scratch(const std::string& name) { return (fs::temp_directory_path() / ("repose_test_" + name)).string(); }

}  // namespace

TEST_CASE("standardised effects rank the cotton screening's factors as its ANOVA does", "[stats][figures]") {
  ResponseSurface fit = cotton_screening();
  std::vector<Effect> effects = standardised_effects(fit, {"A", "B", "C", "D", "E", "F"});
  REQUIRE(effects.size() == 6);
  // Table 4's significant factors, C > E > B by p value, lead the ranking by |t|.
  CHECK(effects[0].term == "C");
  CHECK(effects[1].term == "E");
  CHECK(effects[2].term == "B");
  for (const Effect& e : effects) {
    CHECK(e.effect == Approx(2 * e.coefficient));
    // t^2 is the term's partial F (one df) in the ANOVA.
    CHECK(e.t * e.t == Approx(fit.row(e.term).f).epsilon(1e-9));
  }
  // The t table: t(0.025, 8) = 2.306; Bonferroni over 6 effects t(0.025 / 6, 8) = 3.479.
  CHECK(t_value_limit(0.05, 8) == Approx(2.306).margin(5e-4));
  CHECK(bonferroni_limit(0.05, 6, 8) == Approx(3.479).margin(5e-3));
  CHECK(normal_quantile(0.975) == Approx(1.959964).margin(1e-6));
  CHECK(half_normal_quantiles(4)[0] == Approx(normal_quantile(0.5625)));
}

TEST_CASE("the Pareto chart and half-normal plot show every effect with its sign", "[stats][figures]") {
  ResponseSurface fit = cotton_screening();
  std::vector<Effect> effects = standardised_effects(fit, {"A", "B", "C", "D", "E", "F"});
  Chart::keep_records();
  std::string pareto = scratch("pareto.png"), half = scratch("half_normal.png");
  write_pareto_chart(effects, fit.residual.df, 0.05, "angle", pareto);
  ChartRecord p = Chart::recorded(pareto);
  test::check_figure(p, {"raises angle", "lowers angle", "t-value limit 2.31", "Bonferroni limit 3.48"});
  // One bar per effect: A and F lower the angle in Table 3, the others raise it.
  CHECK(p.points_of(colours::orange, Mark::Bar) == 4);
  CHECK(p.points_of(colours::blue, Mark::Bar) == 2);
  write_half_normal_plot(effects, "angle", half);
  ChartRecord h = Chart::recorded(half);
  test::check_figure(h, {"raises angle", "lowers angle", "noise: line through the smaller half"});
  CHECK(h.points_of(colours::orange, Mark::Square) + h.points_of(colours::blue, Mark::Square) == 6);
  fs::remove(pareto);
  fs::remove(half);
}

TEST_CASE("the steepest-ascent plot and the 3D surface show their series and distinct ticks", "[stats][figures]") {
  Chart::keep_records();
  std::string path = scratch("ascent.png"), surface = scratch("surface_3d.png");
  // The cabbage study's six steepest-ascent points of Table 8 (drawing-plate box, deg).
  write_steepest_ascent_plot({{1, 13.39, 0}, {2, 15.30, 0}, {3, 17.08, 0}, {4, 20.62, 0}, {5, 24.81, 0}, {6, 28.69, 0}},
                             17.56, "angle (deg)", path);
  ChartRecord a = Chart::recorded(path);
  test::check_figure(a, {"angle (deg) (bars: standard error)", "target 17.6"});
  CHECK(a.points_of(colours::blue, Mark::Square) == 6);

  SurfacePicture s;
  s.a0 = 0.2, s.a1 = 0.4, s.b0 = 0.02, s.b1 = 0.04;
  s.f = [](double x, double y) { return 10 + 20 * (x - 0.3) - 100 * (y - 0.03) + 150 * (x - 0.3) * (x - 0.3); };
  s.a_label = "mu_s", s.b_label = "mu_r", s.z_label = "angle (deg)", s.title = "angle over mu_s and mu_r";
  s.runs = {{0.2, 0.02, 9.6}, {0.4, 0.04, 10.6}, {0.3, 0.03, 10.1}};
  write_surface_3d(s, surface);
  ChartRecord r = Chart::recorded(surface);
  test::check_figure(r, {"model (red high, blue low)", "runs"});
  test::check_ticks(r.z_ticks, "z");
  CHECK(r.z_label == "angle (deg)");
  CHECK(r.points_of(colours::black, Mark::Dot) == 3);
  fs::remove(path);
  fs::remove(surface);
}

TEST_CASE("the printed ANOVA keeps its columns apart when a value is as wide as its column", "[stats][report]") {
  // An almost exact straight line: F near 3e5 prints as 2.8...e+05, ten characters in a ten-wide column.
  Eigen::MatrixXd x(8, 1);
  Eigen::VectorXd y(8);
  for (int i = 0; i < 8; ++i) {
    x(i, 0) = -1 + 2.0 * i / 7;
    y[i] = 0.45 + 0.1 * x(i, 0) + 2e-4 * ((i * 5) % 3 - 1);
  }
  ResponseSurface fit = analyse(x, y, build_model(ModelKind::linear, 1));
  std::string text = format_anova(fit, {"e"}, "linear");
  std::istringstream lines(text);
  std::string line;
  std::getline(lines, line);  // the title
  std::getline(lines, line);  // the header
  std::getline(lines, line);  // Model: source, SS, df, MS, F, p ("< 0.0001" is two words), significant
  std::istringstream words(line);
  std::vector<std::string> w{std::istream_iterator<std::string>(words), {}};
  INFO(line);
  REQUIRE(w.size() == 8);
  CHECK(w[0] == "Model");
  CHECK(w[4].size() >= 10);  // as wide as its column
  CHECK(std::stod(w[4]) == Approx(fit.model.f).epsilon(1e-4));
}
