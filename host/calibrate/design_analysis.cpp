#include "calibrate/design_analysis.h"

#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "calibrate/design_runs.h"
#include "stats/anova.h"
#include "stats/calibration_curve.h"
#include "stats/errors.h"
#include "stats/optimize.h"
#include "stats/report.h"

namespace repose::calibrate {

namespace {

double response_of(const RunRecord& r, const std::string& name) {
  auto it = r.responses.find(name);
  if (it == r.responses.end()) throw std::runtime_error("run " + r.spec.id + " has no response '" + name + "'");
  return it->second;
}

double coded_value(const PlanFactor& f, double actual) { return (actual - 0.5 * (f.low + f.high)) / (0.5 * (f.high - f.low)); }
double actual_value(const PlanFactor& f, double coded) { return 0.5 * (f.low + f.high) + coded * 0.5 * (f.high - f.low); }

// Replicate groups: runs at the same design point.
std::vector<std::vector<double>> groups_by_point(const std::vector<RunRecord>& runs, const std::string& response) {
  std::map<int, std::vector<double>> g;
  for (const auto& r : runs) g[r.spec.point].push_back(response_of(r, response));
  std::vector<std::vector<double>> out;
  for (auto& [p, v] : g) out.push_back(v);
  return out;
}

}  // namespace

void pool_replicates(const std::vector<std::vector<double>>& groups, double& sd, int& df) {
  double ss = 0;
  df = 0;
  for (const auto& g : groups) {
    if (g.size() < 2) continue;
    // Deviations from the first value: identical replicates give exactly zero.
    double m = 0;
    for (double v : g) m += v - g[0];
    m /= double(g.size());
    for (double v : g) ss += (v - g[0] - m) * (v - g[0] - m);
    df += int(g.size()) - 1;
  }
  sd = df > 0 ? std::sqrt(ss / df) : 0;
}

namespace {

// One factor swept: a calibration curve through the runs, inverted at the target (or the swept
// value closest to it when out of reach), and the swept values within the tolerance.
void analyse_sweep(const CampaignPlan& plan, const std::vector<RunRecord>& runs, const Eigen::VectorXd& y,
                   CalibrationResult& res, std::ostringstream& text) {
  const int n = int(runs.size());
  const double target = plan.measured, tol = plan.absolute_tolerance();
  res.method = "calibration curve";
  std::vector<double> xs(n), ys(n);
  for (int i = 0; i < n; ++i) {
    xs[i] = runs[i].spec.x[0];
    ys[i] = y[i];
  }
  auto curve = std::make_shared<stats::CalibrationCurve>(stats::fit_curve(xs, ys, plan.design.degree));
  double chosen;
  try {
    chosen = stats::invert(*curve, target);
    res.target_reached = true;
  } catch (const stats::StatsError& e) {
    // Out of reach: the swept value closest to the target, said in the report.
    chosen = curve->x_min;
    for (double v : curve->sweep_x)
      if (std::abs((*curve)(v) - target) < std::abs((*curve)(chosen) - target)) chosen = v;
    text << "The curve cannot be inverted at " << target << ": " << e.what() << "\n";
  }
  text << "Calibration curve (degree " << curve->degree << ", R^2 = " << curve->r2 << "): "
       << plan.response << " = ";
  for (int p = 0; p < curve->coefficients.size(); ++p)
    text << (p ? " + " : "") << curve->coefficients[p] << (p ? " " + plan.factors[0].name : "")
         << (p > 1 ? "^" + std::to_string(p) : "");
  text << "\n";
  const PlanFactor f = plan.factors[0];
  res.chosen = {chosen};
  res.chosen_coded = Eigen::VectorXd::Constant(1, coded_value(f, chosen));
  res.predicted = (*curve)(chosen);
  res.predict = [curve, f](const Eigen::VectorXd& c) { return (*curve)(actual_value(f, c[0])); };
  ParameterEstimate p{f.name, chosen, curve->derivative(chosen), 0, chosen, chosen};
  // The swept values whose curve response lies within the tolerance of the target.
  double lo = chosen, hi = chosen;
  for (int s = 0; s <= 2000; ++s) {
    double v = f.low + (f.high - f.low) * s / 2000.0;
    if (std::abs((*curve)(v) - target) <= tol) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  p.set_low = lo;
  p.set_high = hi;
  res.parameters = {p};
}

// A response surface (reduced backward when asked), the point where it meets the target, each
// parameter's local slope and the extent of the near-target set.
void analyse_surface(const CampaignPlan& plan, const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                     CalibrationResult& res, std::ostringstream& text) {
  const int k = int(plan.factors.size());
  const double target = plan.measured, tol = plan.absolute_tolerance();
  res.method = "response surface";
  auto kind = stats::parse_model_kind(plan.design.model);
  std::vector<stats::Term> terms = stats::build_model(kind, k);
  std::vector<stats::RemovedTerm> removed;
  stats::ResponseSurface fit;
  if (plan.design.reduce > 0) {
    auto red = stats::reduce_backward(x, y, terms, plan.design.reduce, true);
    fit = red.model;
    removed = red.removed;
  } else {
    fit = stats::analyse(x, y, terms);
  }
  std::vector<std::string> names = plan.factor_names();
  std::vector<stats::Factor> ranges;
  for (const auto& f : plan.factors) ranges.push_back({f.name, f.low, f.high});
  text << stats::format_anova(fit, names, plan.design.model) << "\n" << stats::format_fit_statistics(fit) << "\n"
       << stats::format_equations(fit, plan.response, names, ranges);
  for (const auto& r : removed) text << "removed " << r.term << " (p = " << stats::format_p(r.p) << ")\n";
  auto model = std::make_shared<stats::ResponseSurface>(fit);
  stats::Objective objective = [model](const Eigen::VectorXd& c) { return model->predict(c); };
  stats::OptimizeOptions opt;
  opt.tolerance = tol;
  stats::Optimum best = stats::optimize(objective, stats::Box::cube(k, 1.0), {stats::GoalKind::target, target}, opt);
  res.chosen_coded = best.x;
  res.predicted = best.value;
  res.target_reached = best.target_reached;
  res.predict = objective;
  for (int j = 0; j < k; ++j) res.chosen.push_back(actual_value(plan.factors[j], best.x[j]));
  for (int j = 0; j < k; ++j) {
    const PlanFactor& f = plan.factors[j];
    Eigen::VectorXd p = best.x, m = best.x;
    p[j] += 1e-4;
    m[j] -= 1e-4;
    double slope_coded = (model->predict(p) - model->predict(m)) / 2e-4;
    res.parameters.push_back({f.name, res.chosen[j], slope_coded / (0.5 * (f.high - f.low)), 0,
                              actual_value(f, best.set_lower[j]), actual_value(f, best.set_upper[j])});
  }
  text << "\nNear-target set: " << best.set_size << " of " << best.sampled << " sampled points within +-" << tol
       << " of " << target << "\n";
  res.coded_extent = std::max(1.0, x.cwiseAbs().maxCoeff());
}

}  // namespace

CalibrationResult analyse_design(const CampaignPlan& plan, const RunStore& store) {
  const int k = int(plan.factors.size());
  std::vector<RunRecord> runs;
  for (const auto& spec : design_runs(plan)) {
    const RunRecord* r = store.find(spec.id);
    if (!r) throw std::runtime_error("design run " + spec.id + " is missing from " + store.path());
    runs.push_back(*r);
  }
  const int n = int(runs.size());
  Eigen::MatrixXd x(n, k);
  Eigen::VectorXd y(n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < k; ++j) x(i, j) = coded_value(plan.factors[j], runs[i].spec.x[j]);
    y[i] = response_of(runs[i], plan.response);
  }
  CalibrationResult res;
  res.replicate_df = 0;
  pool_replicates(groups_by_point(runs, plan.response), res.replicate_sd, res.replicate_df);
  std::ostringstream text;
  if (plan.design.type == "sweep") analyse_sweep(plan, runs, y, res, text);
  else analyse_surface(plan, x, y, res, text);
  res.model_text = text.str();
  return res;
}

void add_verification(const CampaignPlan& plan, const std::vector<RunRecord>& runs,
                      const std::vector<std::vector<double>>& other_groups, CalibrationResult& res) {
  res.verification = runs;
  std::vector<double> v;
  for (const auto& r : runs) v.push_back(response_of(r, plan.response));
  std::vector<std::vector<double>> groups = other_groups;
  groups.push_back(v);
  pool_replicates(groups, res.replicate_sd, res.replicate_df);
  if (!v.empty()) {
    double d = 0;
    for (double e : v) d += e - v[0];
    d /= double(v.size());
    double ss = 0;
    for (double e : v) ss += (e - v[0] - d) * (e - v[0] - d);
    const double m = v[0] + d;
    res.verification_mean = m;
    res.verification_sd = v.size() > 1 ? std::sqrt(ss / double(v.size() - 1)) : 0;
    res.verification_error = (m - plan.measured) / plan.measured;
  }
  res.sigma_response = std::sqrt(plan.measured_sd * plan.measured_sd + res.replicate_sd * res.replicate_sd);
  for (auto& p : res.parameters)
    p.uncertainty = std::abs(p.slope) > 0 ? res.sigma_response / std::abs(p.slope) : std::numeric_limits<double>::infinity();
}

std::vector<std::vector<double>> design_replicate_groups(const CampaignPlan& plan, const RunStore& store) {
  std::vector<RunRecord> runs;
  for (const auto& spec : design_runs(plan))
    if (const RunRecord* r = store.find(spec.id)) runs.push_back(*r);
  return groups_by_point(runs, plan.response);
}

}  // namespace repose::calibrate
