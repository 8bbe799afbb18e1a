// `repose optimize`: the optimum of fitted models (host/stats) and the set of parameters near it,
// for one response's goal or the overall desirability of several. Every output file is written
// whole or not at all, and every error names the file, line and column to fix.
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
#include "stats/optimize.h"
#include "stats/report.h"
#include "util/number_text.h"

namespace repose::cli {

namespace {

using namespace repose::stats;

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

}  // namespace

std::vector<Verb> optimize_verbs() {
  return {{"optimize", "optimise fitted models; report the set of near-optimal parameters", run_optimize}};
}

}  // namespace repose::cli
