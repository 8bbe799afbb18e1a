// `repose design`, `repose fit`, `repose optimize`, `repose curve`: the calibration statistics
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

std::string num(double v, int digits = 6) {
  if (std::fabs(v) < 1e-12) v = 0;  // coded centres computed as (x - c) / h come out as +-3e-15
  return format_g(v, digits);
}

// Index of a factor given by name or by its letter (A, B, ...).
int find_factor(const std::vector<std::string>& names, const std::string& key, const std::string& where) {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == key) return static_cast<int>(i);
  if (key.size() == 1) {
    int f = factor_from_letter(key[0]);
    if (f >= 0 && f < static_cast<int>(names.size())) return f;
  }
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  throw StatsError(where + ": unknown factor '" + key + "' (factors: " + list + ")");
}

// "NAME=VALUE" -> (name, value).
std::pair<std::string, double> parse_assignment(const std::string& s, const char* option) {
  auto eq = s.find('=');
  double v = 0;
  if (eq == std::string::npos || eq == 0 || !parse_number(s.substr(eq + 1), v))
    throw StatsError(std::string(option) + " '" + s + "' is not NAME=VALUE");
  return {s.substr(0, eq), v};
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
// "min", "max", "target=V", each optionally followed by ":LOW:HIGH" (the acceptable range;
// default: the observed response range of that fit).
DesirabilityGoal parse_goal(const std::string& spec, const SavedFit& fit) {
  auto parts = split(spec, ':');
  DesirabilityGoal g;
  g.low = fit.y_min;
  g.high = fit.y_max;
  const std::string& head = parts[0];
  if (head == "min") g.kind = GoalKind::minimize;
  else if (head == "max") g.kind = GoalKind::maximize;
  else if (head.rfind("target=", 0) == 0) {
    g.kind = GoalKind::target;
    if (!parse_number(head.substr(7), g.target)) throw StatsError("--goal '" + spec + "': bad target value");
  } else {
    throw StatsError("--goal '" + spec + "' is not min, max or target=V (optionally :LOW:HIGH)");
  }
  if (parts.size() == 3) {
    if (!parse_number(parts[1], g.low) || !parse_number(parts[2], g.high))
      throw StatsError("--goal '" + spec + "': bad LOW:HIGH");
  } else if (parts.size() != 1) {
    throw StatsError("--goal '" + spec + "' is not GOAL or GOAL:LOW:HIGH");
  }
  if (!(g.low < g.high)) throw StatsError("--goal '" + spec + "': range reversed or empty");
  if (g.kind == GoalKind::target && (g.target < g.low || g.target > g.high))
    throw StatsError("--goal '" + spec + "': the target lies outside LOW:HIGH");
  return g;
}

// What `repose optimize` was asked.
struct OptimizeRequest {
  std::vector<std::string> fit_paths, goals, fixes, fixes_coded, compare;
  bool minimize = false, maximize = false;
  std::optional<double> target, tolerance;
  std::string within = "cube", json_out;
};

// The optimum found and what it optimised: one response's goal, or the overall desirability.
struct OptimizeOutcome {
  std::vector<SavedFit> fits;
  std::vector<Objective> responses;
  Box box;
  std::vector<std::string> fixed_names;
  Goal goal;
  Optimum best;
  std::string what;  // the response's name, or "desirability"
  bool desirability() const { return what == "desirability"; }
  // A factor's actual value at a coded one (coded when the fit has no ranges).
  double actual(int i, double coded) const {
    return fits[0].ranges.empty() ? coded : fits[0].ranges[size_t(i)].to_actual(coded);
  }
};

std::vector<SavedFit> read_fits(const OptimizeRequest& q) {
  std::vector<SavedFit> fits;
  for (const auto& p : q.fit_paths) fits.push_back(read_fit_file(p));
  for (const auto& f : fits)
    if (f.factor_names != fits[0].factor_names)
      throw StatsError(f.source + ": its factors differ from those of " + fits[0].source);
  const bool single = fits.size() == 1;
  if (single && !q.goals.empty() && (q.minimize || q.maximize || q.target))
    throw StatsError("give either --minimize/--maximize/--target or --goal");
  if (single && q.goals.empty() && !q.minimize && !q.maximize && !q.target)
    throw StatsError("say what to do: --minimize, --maximize or --target V");
  if (!single && q.goals.size() != fits.size())
    throw StatsError("several fits need one --goal each (" + std::to_string(fits.size()) + " fits, " +
                     std::to_string(q.goals.size()) + " goals)");
  return fits;
}

// The region searched (--within) with the factors held by --fix and --fix-coded.
Box optimisation_box(const OptimizeRequest& q, const SavedFit& first, std::vector<std::string>& fixed_names) {
  const int k = static_cast<int>(first.factor_names.size());
  Box box;
  if (q.within == "axial" || q.within == "data") {
    box = Box{first.coded_min, first.coded_max};
  } else if (q.within == "cube") {
    box = Box::cube(k, 1);
  } else {
    double r = 0;
    if (!parse_number(q.within, r) || !(r > 0))
      throw StatsError("--within '" + q.within + "' is not cube, axial or a radius");
    box = Box::cube(k, r);
  }
  for (const auto& s : q.fixes) {
    auto [name, v] = parse_assignment(s, "--fix");
    int i = find_factor(first.factor_names, name, "--fix");
    if (first.ranges.empty()) throw StatsError("--fix needs factor ranges in the fit; use --fix-coded");
    box.fix(i, first.ranges[i].to_coded(v));
    fixed_names.push_back(first.factor_names[i]);
  }
  for (const auto& s : q.fixes_coded) {
    auto [name, v] = parse_assignment(s, "--fix-coded");
    int i = find_factor(first.factor_names, name, "--fix-coded");
    box.fix(i, v);
    fixed_names.push_back(first.factor_names[i]);
  }
  return box;
}

OptimizeOutcome find_optimum(const OptimizeRequest& q) {
  OptimizeOutcome o;
  o.fits = read_fits(q);
  o.box = optimisation_box(q, o.fits[0], o.fixed_names);
  OptimizeOptions opt;
  if (q.tolerance) opt.tolerance = *q.tolerance;
  for (const auto& f : o.fits) o.responses.push_back([p = f.coded](const Eigen::VectorXd& x) { return p(x); });
  const bool single = o.fits.size() == 1;
  if (single && q.goals.empty()) {
    o.goal.kind = q.minimize ? GoalKind::minimize : q.maximize ? GoalKind::maximize : GoalKind::target;
    if (q.target) o.goal.target = *q.target;
    o.best = optimize(o.responses[0], o.box, o.goal, opt);
    o.what = o.fits[0].response;
    return o;
  }
  std::vector<DesirabilityGoal> dg;
  for (size_t i = 0; i < o.fits.size(); ++i) dg.push_back(parse_goal(q.goals[i], o.fits[i]));
  if (single) {
    // One fit with --goal: plain optimisation of that goal.
    o.goal.kind = dg[0].kind;
    o.goal.target = dg[0].target;
    o.best = optimize(o.responses[0], o.box, o.goal, opt);
    o.what = o.fits[0].response;
  } else {
    o.best = optimize_desirability(o.responses, dg, o.box, opt);
    o.what = "desirability";
  }
  return o;
}

void print_optimum(const OptimizeOutcome& o) {
  const SavedFit& first = o.fits[0];
  const int k = static_cast<int>(first.factor_names.size());
  const Optimum& best = o.best;
  std::printf("Goal: %s %s", o.desirability() ? "maximise overall" : goal_name(o.goal).c_str(), o.what.c_str());
  if (!o.fixed_names.empty()) {
    std::printf("; fixed:");
    for (const auto& n : o.fixed_names) std::printf(" %s", n.c_str());
  }
  std::printf("\nRegion (coded):");
  for (int i = 0; i < k; ++i)
    std::printf(" %s [%s, %s]", first.factor_names[i].c_str(), num(o.box.lower[i]).c_str(), num(o.box.upper[i]).c_str());
  std::printf("\n\nOptimum: %s = %s\n", o.what.c_str(), num(best.value, 8).c_str());
  if (o.desirability())
    for (size_t r = 0; r < o.fits.size(); ++r)
      std::printf("  %s = %s\n", o.fits[r].response.c_str(), num(o.responses[r](best.x), 8).c_str());
  for (int i = 0; i < k; ++i)
    std::printf("  %-12s %-12s (coded %s)\n", first.factor_names[i].c_str(), num(o.actual(i, best.x[i]), 8).c_str(),
                num(best.x[i], 6).c_str());
  if (o.goal.kind == GoalKind::target && !o.desirability() && !best.target_reached)
    std::printf("  the target %s is NOT reachable in this region (closest %s)\n", num(o.goal.target).c_str(),
                num(best.value).c_str());
}

// The near-optimal set: its extent per factor, the direction it extends along, its members.
void print_near_set(const OptimizeOutcome& o) {
  const SavedFit& first = o.fits[0];
  const int k = static_cast<int>(first.factor_names.size());
  const Optimum& best = o.best;
  const std::string& what = o.what;
  std::string band = o.desirability()                ? "desirability within " + num(best.tolerance) + " of the best"
                     : o.goal.kind == GoalKind::target ? what + " within " + num(best.tolerance) + " of the target"
                                                       : what + " within " + num(best.tolerance) + " of the optimum";
  std::printf("\nNear-optimal set (%s): %d of %d sampled points\n", band.c_str(), best.set_size, best.sampled);
  std::printf("  %-12s %-26s %s\n", "factor", "coded extent", "actual extent");
  for (int i = 0; i < k; ++i)
    std::printf("  %-12s %-26s %s .. %s\n", first.factor_names[i].c_str(),
                (num(best.set_lower[i], 4) + " .. " + num(best.set_upper[i], 4)).c_str(),
                num(o.actual(i, best.set_lower[i]), 6).c_str(), num(o.actual(i, best.set_upper[i]), 6).c_str());
  if (best.principal_direction.norm() > 0) {
    std::string dir;
    for (int i = 0; i < k; ++i) {
      double c = best.principal_direction[i];
      if (std::fabs(c) < 0.05) continue;
      dir += (dir.empty() ? (c < 0 ? "-" : "") : (c < 0 ? " - " : " + ")) + num(std::fabs(c), 2) + " " + first.factor_names[i];
    }
    std::printf("  The set extends most along (coded) %s: moving along it barely changes %s, so\n"
                "  this response cannot tell these parameter sets apart; a further test that responds\n"
                "  to that combination of factors is needed to separate them.\n", dir.c_str(), what.c_str());
  }
  std::printf("\nRepresentative members (the optimum first):\n ");
  for (int i = 0; i < k; ++i) std::printf(" %12s", first.factor_names[i].c_str());
  std::printf(" %12s\n", what.c_str());
  for (size_t r = 0; r < best.representatives.size(); ++r) {
    std::printf(" ");
    for (int i = 0; i < k; ++i) std::printf(" %12s", num(o.actual(i, best.representatives[r][i])).c_str());
    std::printf(" %12s\n", num(best.representative_values[r]).c_str());
  }
}

// --compare: a reported point against the optimum, printed and as JSON.
Json compare_with_optimum(const OptimizeOutcome& o, const std::vector<std::string>& compare) {
  if (o.desirability()) throw StatsError("--compare works with a single response");
  const SavedFit& first = o.fits[0];
  const int k = static_cast<int>(first.factor_names.size());
  Eigen::VectorXd point = o.best.x;
  for (const auto& s : compare) {
    auto [name, v] = parse_assignment(s, "--compare");
    int i = find_factor(first.factor_names, name, "--compare");
    point[i] = first.ranges.empty() ? v : first.ranges[i].to_coded(v);
  }
  PointComparison c = compare_point(o.responses[0], o.goal, o.best, o.box, point);
  std::printf("\nCompared point:");
  for (int i = 0; i < k; ++i) std::printf(" %s=%s", first.factor_names[i].c_str(), num(o.actual(i, point[i])).c_str());
  std::printf("\n  %s there = %s; optimum %s; %s by %s\n", o.what.c_str(), num(c.value, 6).c_str(),
              num(o.best.value, 6).c_str(), c.gap > 0 ? "worse" : "not worse", num(std::fabs(c.gap), 4).c_str());
  if (!c.inside_box) std::printf("  the point lies outside the optimisation region\n");
  std::printf("  %s\n", c.in_near_set ? "it belongs to the near-optimal set"
                                        : "it is NOT near-optimal: the fitted model disagrees with this point");
  Json cj = Json::object();
  Json p = Json::array();
  for (int i = 0; i < k; ++i) p.push(o.actual(i, point[i]));
  cj.set("point", p);
  cj.set("value", c.value);
  cj.set("gap", c.gap);
  cj.set("near_optimal", c.in_near_set);
  return cj;
}

// The optimum and the near-optimal set in actual units (--json), after `out`'s comparison.
void add_optimum_json(const OptimizeOutcome& o, Json& out) {
  const SavedFit& first = o.fits[0];
  const int k = static_cast<int>(first.factor_names.size());
  const Optimum& best = o.best;
  Json names = Json::array(), x = Json::array(), lo = Json::array(), hi = Json::array(), reps = Json::array();
  for (int i = 0; i < k; ++i) {
    names.push(first.factor_names[i]);
    x.push(o.actual(i, best.x[i]));
    lo.push(o.actual(i, best.set_lower[i]));
    hi.push(o.actual(i, best.set_upper[i]));
  }
  for (size_t r = 0; r < best.representatives.size(); ++r) {
    Json row = Json::array();
    for (int i = 0; i < k; ++i) row.push(o.actual(i, best.representatives[r][i]));
    row.push(best.representative_values[r]);
    reps.push(row);
  }
  out.set("goal", o.desirability() ? std::string("desirability") : goal_name(o.goal));
  out.set("factors", names);
  out.set("optimum", x);
  out.set("value", best.value);
  out.set("tolerance", best.tolerance);
  out.set("set_size", best.set_size);
  out.set("sampled", best.sampled);
  out.set("set_lower", lo);
  out.set("set_upper", hi);
  out.set("representatives", reps);
}

int run_optimize(int argc, char** argv) {
  CLI::App app{"Optimise fitted models (repose fit --json) inside the design region, and report "
               "every parameter set that does about as well."};
  OptimizeRequest q;
  app.add_option("fits", q.fit_paths, "fit files; several with --goal each: desirability")->required();
  auto* o_min = app.add_flag("--minimize,--minimise", q.minimize, "minimise the response");
  auto* o_max = app.add_flag("--maximize,--maximise", q.maximize, "maximise the response");
  auto* o_tgt = app.add_option("--target", q.target, "bring the response to this value")->check(finite_number());
  o_min->excludes(o_max)->excludes(o_tgt);
  o_max->excludes(o_tgt);
  app.add_option("--goal", q.goals, "one per fit: min, max or target=V, optionally :LOW:HIGH")->delimiter(',');
  app.add_option("--fix", q.fixes, "NAME=VALUE: hold a factor at an actual value")->delimiter(',');
  app.add_option("--fix-coded", q.fixes_coded, "NAME=VALUE: hold a factor at a coded value")->delimiter(',');
  app.add_option("--within", q.within,
                 "region: cube (the factorial +-1, default, as Design-Expert), axial (the design's extent: +-alpha of a "
                 "central composite design) or a coded radius");
  app.add_option("--tolerance", q.tolerance, "width of the reported near-optimal set, in response units")->check(finite_positive());
  app.add_option("--compare", q.compare, "NAME=VALUE,...: a reported point (actual units) to compare")->delimiter(',');
  app.add_option("--json", q.json_out, "write the optimum and the near-optimal set to this file");
  REPOSE_PARSE(app, argc, argv);

  OptimizeOutcome o = find_optimum(q);
  print_optimum(o);
  print_near_set(o);
  Json out = Json::object();
  if (!q.compare.empty()) out.set("compared", compare_with_optimum(o, q.compare));
  if (!q.json_out.empty()) {
    add_optimum_json(o, out);
    repose::write_file_atomically(q.json_out, out.dump());
    std::printf("\nwrote %s\n", q.json_out.c_str());
  }
  return 0;
}

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
      {"optimize", "optimise fitted models; report the set of near-optimal parameters", run_optimize},
      {"curve", "fit a calibration curve to a sweep and invert it at a measured value", run_curve},
      {"ascent-plot", "plot the response along a steepest-ascent path against its target", run_ascent_plot},
  };
}

}  // namespace repose::cli
