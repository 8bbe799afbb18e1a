// `repose design`, `repose fit`, `repose ascent-plot`, `repose curve`: the calibration statistics
// (host/stats) on plain CSV tables. Every output file is written whole or not at all
// (temporary file + rename), and every error names the file, line and column to fix.
#include <filesystem>
#include <map>
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "cli/cli_checks.h"
#include "cli/stats_text.h"
#include "cli/verbs.h"
#include "io/provenance.h"
#include "stats/anova.h"
#include "util/atomic_file.h"
#include "stats/calibration_curve.h"
#include "stats/csv_table.h"
#include "stats/dataset.h"
#include "stats/design.h"
#include "stats/errors.h"
#include "stats/fit_file.h"
#include "stats/json.h"
#include "stats/design_figures.h"
#include "stats/optimize.h"
#include "stats/report.h"
#include "util/number_text.h"

namespace repose::cli {

namespace {

using namespace repose::stats;

std::string join_args(int argc, char** argv) {
  std::string s;
  for (int i = 0; i < argc; ++i) s += (i ? " " : "") + std::string(argv[i]);
  return s;
}

// --type path: steps along the steepest ascent (or descent) of a first-order fit's coded slopes.
Design path_design(const std::string& fit_path, double step, int steps, bool descent) {
  if (fit_path.empty()) throw StatsError("--type path needs --fit FIT.json (a first-order fit)");
  SavedFit fit = read_fit_file(fit_path);
  if (fit.ranges.empty())
    throw StatsError(fit_path + ": the fit has no factor ranges (fit with --coded or --ranges)");
  const int k = static_cast<int>(fit.factor_names.size());
  Eigen::VectorXd slopes(k);
  for (int i = 0; i < k; ++i) {
    Term t{std::vector<int>(k, 0)};
    t.powers[i] = 1;
    slopes[i] = fit.coded.coefficient(t);
  }
  return steepest_path(fit.ranges, slopes, step, steps, !descent);
}

// The screening and response-surface designs of --factors NAME:LOW:HIGH,...
Design factor_design(const std::string& type, const std::string& factor_list, int centre, const std::string& alpha,
                     std::vector<std::string> generators, int fraction) {
  if (factor_list.empty()) throw StatsError("--factors NAME:LOW:HIGH,... is required");
  std::vector<Factor> factors = parse_factors(factor_list);
  int centres = centre >= 0 ? centre : type == "ccd" ? 6 : type == "bbd" ? 5 : 0;
  if (type == "pb12") return plackett_burman(12, factors, centres);
  if (type == "pb20") return plackett_burman(20, factors, centres);
  if (type == "factorial") return full_factorial(factors, centres);
  if (type == "fractional") {
    if (generators.empty() && fraction <= 0)
      throw StatsError("--type fractional needs --generators D=ABC,... or --fraction P");
    if (generators.empty()) generators = default_generators(static_cast<int>(factors.size()), fraction);
    return fractional_factorial(factors, generators, centres);
  }
  if (type == "ccd") return central_composite(factors, parse_alpha(alpha), centres);
  return box_behnken(factors, centres);
}

// The design's line in the CSV's comments: runs by point type, alpha, generators, run order.
std::string design_summary(const Design& d, const std::optional<std::uint64_t>& seed) {
  std::string summary = std::to_string(d.runs()) + " runs";
  int counts[5] = {0, 0, 0, 0, 0};
  for (auto p : d.points) ++counts[static_cast<int>(p)];
  for (int t = 0; t < 5; ++t)
    if (counts[t]) summary += ", " + std::to_string(counts[t]) + " " + point_type_name(static_cast<PointType>(t));
  if (d.type == "ccd") summary += "; alpha = " + num(d.alpha, 10);
  if (!d.generators.empty()) {
    summary += "; generators";
    for (const auto& g : d.generators) summary += " " + g;
  }
  if (!d.dummies.empty()) summary += "; " + std::to_string(d.dummies.size()) + " dummy columns";
  summary += seed ? "; run order randomised with seed " + std::to_string(*seed) : "; standard order";
  return summary;
}

// ---------------------------------------------------------------------------------------
int run_design(int argc, char** argv) {
  CLI::App app{"Write an experimental design (coded and actual values) as CSV."};
  std::string type, factor_list, alpha = "rotatable", out, fit_path;
  std::vector<std::string> generators;
  int centre = -1, fraction = 0, steps = 5;
  double step = 1;
  bool descent = false;
  std::optional<std::uint64_t> seed;
  app.add_option("--type", type, "pb12, pb20, factorial, fractional, ccd, bbd, or path (steepest ascent)")
      ->required()
      ->check(CLI::IsMember({"pb12", "pb20", "factorial", "fractional", "ccd", "bbd", "path"}));
  app.add_option("--factors", factor_list, "NAME:LOW:HIGH,... actual values coded -1 and +1");
  app.add_option("--centre,--center", centre,
                 "centre points (default: 6 for ccd, 5 for bbd, 0 otherwise)")->check(whole_number(0, 1000));
  app.add_option("--alpha", alpha, "ccd axial distance: rotatable, orthogonal, face, or a number");
  app.add_option("--generators", generators, "fractional: generators such as D=ABC,E=-ABD")->delimiter(',');
  app.add_option("--fraction", fraction, "fractional: p of 2^(k-p), with standard generators")->check(whole_number(0, 30));
  app.add_option("--seed", seed, "randomise the run order with this seed (std::mt19937_64)");
  app.add_option("--fit", fit_path, "path: a first-order fit (repose fit --json) to follow");
  app.add_option("--steps", steps, "path: number of steps (default 5)")->check(whole_number(1, 1000));
  app.add_option("--step", step, "path: coded step of the factor with the largest effect (default 1)")->check(finite_positive());
  app.add_flag("--descent", descent, "path: descend instead of ascend");
  app.add_option("--out", out, "output CSV (default: standard output)")->check(non_empty_path());
  REPOSE_PARSE(app, argc, argv);

  Design d = type == "path" ? path_design(fit_path, step, steps, descent)
                            : factor_design(type, factor_list, centre, alpha, generators, fraction);
  if (seed) randomise_run_order(d, *seed);

  std::vector<std::string> comments = {"repose design: " + join_args(argc - 1, argv + 1)};
  const std::string summary = design_summary(d, seed);
  comments.push_back(summary);
  std::string csv = format_csv(design_table(d), comments);
  if (out.empty()) {
    std::fputs(csv.c_str(), stdout);
  } else {
    repose::write_file_atomically(out, csv);
    std::printf("wrote %s: %s\n", out.c_str(), summary.c_str());
  }
  return 0;
}

// ---------------------------------------------------------------------------------------
// The table's rows as coded factors and the response: --coded codes actual columns with its
// ranges, --ranges gives coded columns their actual ranges, --snap-alpha puts axial levels
// printed rounded at the exact alpha.
DataSet fit_data(const Table& table, const std::vector<std::string>& factors, const std::string& response,
                 const std::vector<std::string>& coded, const std::vector<std::string>& ranges, const std::string& snap) {
  auto parse_ranges = [&](const std::vector<std::string>& specs, const char* option) {
    if (specs.size() != factors.size())
      throw StatsError(std::string(option) + " needs one LOW:HIGH per factor: " + std::to_string(factors.size()) +
                       " factors, " + std::to_string(specs.size()) + " ranges");
    std::vector<Factor> out;
    for (size_t i = 0; i < specs.size(); ++i) out.push_back(parse_range(factors[i], specs[i]));
    return out;
  };
  if (coded.empty() && ranges.empty()) require_coded_columns(table, factors);
  DataSet data = dataset_from_table(table, factors, response, coded.empty() ? std::vector<Factor>{} : parse_ranges(coded, "--coded"));
  if (!ranges.empty()) data.ranges = parse_ranges(ranges, "--ranges");
  const int k = static_cast<int>(factors.size());
  if (!snap.empty()) {
    double alpha = snap == "rotatable" ? std::pow(std::ldexp(1.0, k), 0.25) : 0;
    if (snap != "rotatable" && (!parse_number(snap, alpha) || !(alpha > 0)))
      throw StatsError("--snap-alpha '" + snap + "' is not rotatable or a positive number");
    int n = snap_to_alpha(data.coded, alpha);
    std::printf("axial levels: %d coded values set to +-%.6f\n", n, alpha);
  }
  return data;
}

struct ChosenFit {
  std::optional<Reduction> result;
  std::string model;  // its kind's name
};

// --model, or for "auto" the largest of quadratic, interaction, linear that the design can
// estimate; reduced backward when --reduce is given.
ChosenFit fit_largest_model(const DataSet& data, const std::string& model, std::optional<double> reduce, bool hierarchy,
                            SumOfSquaresType ss_type, const std::string& table_path) {
  const int k = static_cast<int>(data.coded.cols());
  std::vector<std::string> candidates = model == "auto" ? std::vector<std::string>{"quadratic", "interaction", "linear"}
                                                        : std::vector<std::string>{model};
  ChosenFit out;
  for (size_t c = 0; c < candidates.size() && !out.result; ++c) {
    auto terms = build_model(parse_model_kind(candidates[c]), k);
    try {
      if (reduce) {
        out.result = reduce_backward(data.coded, data.y, terms, *reduce, hierarchy, ss_type);
      } else {
        out.result = Reduction{analyse(data.coded, data.y, terms, ss_type), {}};
      }
      out.model = model_kind_name(parse_model_kind(candidates[c]));
    } catch (const ModelError& e) {
      if (c + 1 == candidates.size()) throw ModelError(table_path + ": " + e.what());
      std::printf("%s model not estimable (%s); trying a smaller one\n", candidates[c].c_str(), e.what());
    }
  }
  return out;
}

// Design-Expert's views of a fit (stats/design_figures.h) into `dir`: the Pareto chart and the
// half-normal plot of its effects, and with two factors or more its surface over the first two
// (the others at their centre) in 3D. Returns the files written.
std::vector<std::string> write_fit_figures(const ResponseSurface& fit, const DataSet& data, const std::string& dir) {
  std::filesystem::create_directories(dir);
  std::vector<std::string> files;
  if (fit.residual.df > 0) {
    std::vector<Effect> effects = standardised_effects(fit, data.factor_names);
    write_pareto_chart(effects, fit.residual.df, 0.05, data.response, dir + "/pareto.png");
    write_half_normal_plot(effects, data.response, dir + "/half_normal.png");
    files = {"pareto.png", "half_normal.png"};
  }
  if (data.factor_names.size() >= 2) {
    auto range = [&](int i) { return data.ranges.empty() ? Factor{data.factor_names[size_t(i)], -1, 1} : data.ranges[size_t(i)]; };
    Factor a = range(0), b = range(1);
    // The design's extent in the first two factors (its axial points included).
    double e = std::max({1.0, data.coded.col(0).cwiseAbs().maxCoeff(), data.coded.col(1).cwiseAbs().maxCoeff()});
    SurfacePicture s;
    s.f = [&](double x, double y) {
      Eigen::VectorXd c = Eigen::VectorXd::Zero(long(data.factor_names.size()));
      c[0] = a.to_coded(x);
      c[1] = b.to_coded(y);
      return fit.predict(c);
    };
    s.a0 = a.to_actual(-e), s.a1 = a.to_actual(e), s.b0 = b.to_actual(-e), s.b1 = b.to_actual(e);
    s.a_label = data.factor_names[0];
    s.b_label = data.factor_names[1];
    s.z_label = data.response;
    s.title = data.response + ": the fitted model over " + s.a_label + " and " + s.b_label +
              (data.factor_names.size() > 2 ? " (others at their centre)" : "");
    for (long r = 0; r < data.coded.rows(); ++r)
      if (data.factor_names.size() == 2 || data.coded.row(r).tail(data.coded.cols() - 2).isZero())
        s.runs.push_back({a.to_actual(data.coded(r, 0)), b.to_actual(data.coded(r, 1)), data.y[r]});
    write_surface_3d(s, dir + "/surface_3d.png");
    files.push_back("surface_3d.png");
  }
  return files;
}

int run_fit(int argc, char** argv) {
  CLI::App app{"Fit a polynomial model to a CSV table and print its ANOVA like Design-Expert."};
  std::string table_path, response, model = "auto", json_out, snap, ss = "partial";
  std::vector<std::string> factors, coded, ranges;
  std::optional<double> reduce;
  bool no_hierarchy = false;
  app.add_option("table", table_path, "CSV table with one row per run")->required();
  app.add_option("--response", response, "response column")->required();
  app.add_option("--factors", factors, "factor columns, e.g. A,B,C")->required()->delimiter(',');
  app.add_option("--model", model, "linear, interaction, quadratic, cubic, or auto (largest the design supports)")
      ->check(CLI::IsMember({"auto", "linear", "interaction", "2fi", "quadratic", "cubic"}));
  app.add_option("--coded", coded,
                 "LOW:HIGH per factor: the columns hold actual values, coded with these ranges")
      ->delimiter(',');
  app.add_option("--ranges", ranges,
                 "LOW:HIGH per factor: the columns are coded already; the ranges give the actual equation")
      ->delimiter(',');
  app.add_option("--snap-alpha", snap,
                 "replace axial levels printed rounded (1.682) by the exact alpha: rotatable or a number");
  app.add_option("--reduce", reduce, "drop terms with p above this value, one at a time, keeping hierarchy")->check(finite_between(1e-12, 1));
  app.add_flag("--no-hierarchy", no_hierarchy, "with --reduce: allow dropping terms that others contain");
  app.add_option("--ss", ss, "per-term sums of squares: partial (Type III) or sequential (Type I)")
      ->check(CLI::IsMember({"partial", "sequential"}));
  app.add_option("--json", json_out, "write the fit (for repose optimize) to this file");
  std::string figures;
  app.add_option("--figures", figures,
                 "write Design-Expert's views into this folder: Pareto chart and half-normal plot of the effects, the "
                 "surface in 3D");
  REPOSE_PARSE(app, argc, argv);
  if (!coded.empty() && !ranges.empty()) throw StatsError("give --coded or --ranges, not both");

  Table table = read_csv(table_path);
  DataSet data = fit_data(table, factors, response, coded, ranges, snap);
  SumOfSquaresType ss_type = ss == "partial" ? SumOfSquaresType::partial : SumOfSquaresType::sequential;

  const ChosenFit chosen_fit = fit_largest_model(data, model, reduce, !no_hierarchy, ss_type, table_path);
  const std::optional<Reduction>& result = chosen_fit.result;
  const std::string& chosen = chosen_fit.model;
  const ResponseSurface& fit = result->model;
  std::printf("%s: %d runs, response %s\n\n", table_path.c_str(), table.rows(), response.c_str());
  std::fputs(format_anova(fit, factors, chosen).c_str(), stdout);
  if (!result->removed.empty()) {
    std::printf("Removed (p > %s):", num(*reduce).c_str());
    for (const auto& r : result->removed) std::printf(" %s (p = %s)", r.term.c_str(), format_p(r.p).c_str());
    std::printf("\n");
  }
  std::printf("\n%s\n%s\n%s", format_fit_statistics(fit).c_str(), format_coefficients(fit).c_str(),
              format_equations(fit, response, factors, data.ranges).c_str());
  if (!figures.empty()) {
    std::printf("wrote");
    for (const std::string& f : write_fit_figures(fit, data, figures)) std::printf(" %s/%s", figures.c_str(), f.c_str());
    std::printf("\n");
  }
  if (!json_out.empty()) {
    Json saved = fit_to_json(fit, data, table_path, chosen, result->removed);
    saved.set("provenance", Json::parse(input_provenance({table_path}).dump(), "provenance"));
    repose::write_file_atomically(json_out, saved.dump());
    std::printf("wrote %s\n", json_out.c_str());
  }
  return 0;
}

// ---------------------------------------------------------------------------------------
// ---------------------------------------------------------------------------------------
// The response along a steepest-ascent path, rows grouped by step (replicates: mean and standard
// error), against the target.
int run_ascent_plot(int argc, char** argv) {
  CLI::App app{"Plot the response along a steepest-ascent (or descent) path against its target."};
  std::string path, step_column = "step", response, png;
  double target = 0;
  app.add_option("table", path, "CSV table of the path's runs (repose design --type path, with the response added)")
      ->required();
  app.add_option("--step", step_column, "step column (default step)");
  app.add_option("--response", response, "response column")->required();
  app.add_option("--target", target, "the value the path seeks (the measured response)")->required()->check(finite_number());
  app.add_option("--png", png, "the figure to write")->required();
  CLI11_PARSE(app, argc, argv);
  Table t = read_csv(path);
  std::vector<double> steps = t.numeric_column(step_column), y = t.numeric_column(response);
  std::map<double, std::vector<double>> by_step;
  for (size_t r = 0; r < steps.size(); ++r) by_step[steps[r]].push_back(y[r]);
  std::vector<PathPoint> points;
  for (const auto& [step, values] : by_step) {
    double n = double(values.size()), mean = 0, var = 0;
    for (double v : values) mean += v / n;
    for (double v : values) var += (v - mean) * (v - mean) / std::max(1.0, n - 1);
    points.push_back({step, mean, n > 1 ? std::sqrt(var / n) : 0});
    std::printf("step %s: %s = %s (%zu run%s)\n", num(step).c_str(), response.c_str(), num(mean).c_str(), values.size(),
                values.size() == 1 ? "" : "s");
  }
  write_steepest_ascent_plot(points, target, response, png);
  std::printf("wrote %s\n", png.c_str());
  return 0;
}

// ---------------------------------------------------------------------------------------
int run_curve(int argc, char** argv) {
  CLI::App app{"Fit a calibration curve to a one-parameter sweep and read off the parameter at a measured value."};
  std::string path, xcol, ycol;
  double at = 0;
  int degree = 3;
  app.add_option("sweep", path, "CSV table of the sweep")->required();
  app.add_option("--x", xcol, "swept parameter column")->required();
  app.add_option("--y", ycol, "response column")->required();
  app.add_option("--at", at, "measured response to invert")->required()->check(finite_number());
  app.add_option("--degree", degree, "polynomial degree (default 3)")->check(whole_number(1, 9));
  REPOSE_PARSE(app, argc, argv);
  Table t = read_csv(path);
  std::vector<double> x = t.numeric_column(xcol), y = t.numeric_column(ycol);
  CalibrationCurve c;
  try {
    c = fit_curve(x, y, degree);
  } catch (const CurveError& e) {
    throw CurveError(path + ": " + e.what());
  }
  std::printf("%s: %d points, %s swept over [%s, %s]\n", path.c_str(), t.rows(), xcol.c_str(), num(c.x_min).c_str(),
              num(c.x_max).c_str());
  std::printf("%s =", ycol.c_str());
  for (Eigen::Index i = c.coefficients.size() - 1; i >= 0; --i) {
    double v = c.coefficients[i];
    std::printf(" %s %s", v < 0 ? "-" : "+", num(std::fabs(v), 8).c_str());
    if (i > 0) std::printf(" %s%s", xcol.c_str(), i > 1 ? ("^" + std::to_string(i)).c_str() : "");
  }
  std::printf("   (R^2 = %.6f)\n", c.r2);
  double xv;
  try {
    xv = invert(c, at);
  } catch (const CurveError& e) {
    throw CurveError(path + ": " + e.what());
  }
  std::printf("%s = %s at %s = %s\n", xcol.c_str(), num(xv, 8).c_str(), ycol.c_str(), num(at).c_str());
  return 0;
}

}  // namespace

std::vector<Verb> stats_verbs() {
  return {
      {"design", "write a design (PB, factorial, fractional, CCD, BBD, steepest path) as CSV", run_design},
      {"fit", "fit a model to a CSV table; Design-Expert style ANOVA and equations", run_fit},
      {"curve", "fit a calibration curve to a sweep and invert it at a measured value", run_curve},
      {"ascent-plot", "plot the response along a steepest-ascent path against its target", run_ascent_plot},
  };
}

}  // namespace repose::cli
