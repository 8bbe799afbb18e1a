#include "diagnosis/model_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stats/local_search.h"

namespace repose {

std::vector<double> group_chi_squares(const Observations& obs, const Prediction& predicted, const Prediction* target) {
  size_t groups = obs.groups.size();
  std::vector<double> z(groups), out(groups);
  for (size_t g = 0; g < groups; ++g) {
    const ObservationGroup& grp = obs.groups[g];
    double n = double(grp.values.size());
    double v = predicted.var.empty() ? 0.0 : predicted.var[g];
    double V = grp.sigma_given ? grp.sd * grp.sd + v : grp.sd * grp.sd;
    double var_mean = V / n + predicted.variance_of_mean(g);
    double mean = target ? target->mean[g] : grp.mean;
    z[g] = (mean - predicted.mean[g]) / std::sqrt(var_mean);
    if (grp.sigma_given && grp.values.size() >= 2) {
      double s2 = target ? grp.sd * grp.sd + (target->var.empty() ? 0.0 : target->var[g]) : grp.s2;
      double q = std::max(s2, 1e-300) / V;
      out[g] = (n - 1) * (q - 1 - std::log(q));
    }
  }
  for (size_t g = 0; g < groups; ++g) {
    const ObservationGroup& grp = obs.groups[g];
    double rho = grp.series ? obs.noise.at(grp.measure).rho : 0.0;
    double w = z[g];
    if (grp.previous >= 0 && rho > 0) w = (z[g] - rho * z[size_t(grp.previous)]) / std::sqrt(1 - rho * rho);
    out[g] += w * w;
  }
  return out;
}

double chi_square(const Observations& obs, const Prediction& predicted, const std::vector<char>& use,
                  const Prediction* target) {
  std::vector<double> terms = group_chi_squares(obs, predicted, target);
  double chi2 = 0;
  for (size_t g = 0; g < obs.groups.size(); ++g)
    if (use[obs.groups[g].condition]) chi2 += terms[g];
  return chi2;
}

ShrunkChange shrink_change(const Observations& obs, const Prediction& baseline, const Prediction& candidate) {
  ShrunkChange out;
  out.prediction = candidate;
  size_t groups = obs.groups.size();
  double d2 = 0;
  int scattered = 0;  // groups whose means scatter (a measure that never varies is left out of D)
  for (size_t g = 0; g < groups; ++g) {
    double scatter = baseline.variance_of_mean(g) + candidate.variance_of_mean(g);
    if (!(scatter > 0)) continue;
    double d = candidate.mean[g] - baseline.mean[g];
    d2 += d * d / scatter;
    ++scattered;
  }
  out.d2 = d2;
  if (scattered < 3) return out;  // a deterministic pair (exact change), or too few for Stein
  double s = std::max(0.0, 1.0 - double(scattered - 2) / std::max(d2, 1e-300));
  out.shrinkage = s;
  Prediction& p = out.prediction;
  p.mean_var.assign(groups, 0.0);
  for (size_t g = 0; g < groups; ++g) {
    p.mean[g] = baseline.mean[g] + s * (candidate.mean[g] - baseline.mean[g]);
    p.mean_var[g] = (1 - s) * (1 - s) * baseline.variance_of_mean(g) + s * s * candidate.variance_of_mean(g);
  }
  return out;
}

int score_terms(const Observations& obs) {
  int terms = 0;
  for (const auto& g : obs.groups) terms += 1 + (g.sigma_given && g.values.size() >= 2 ? 1 : 0);
  return terms;
}

namespace {

// The start of a fit whose last parameters have no start value: the first of them scanned over
// its range, the started ones refitted at each point (a profile: they trade off against each
// other), and the best point kept. The range's low end is the extension nearly off, so the fit
// starts no worse than the model without it.
std::vector<double> profile_start(const stats::UnitObjective& objective, const std::vector<double>& u0, size_t started,
                                  bool expensive) {
  std::vector<size_t> held(started);
  for (size_t j = 0; j < held.size(); ++j) held[j] = j;
  double best = std::numeric_limits<double>::infinity();
  std::vector<double> best_u = u0;
  // A heap costs ~1000 drops: a coarser profile (6 points, 8 evaluations each) there.
  int points = expensive ? 5 : 9, inner = expensive ? 8 : 14;
  for (int i = 0; i <= points; ++i) {
    std::vector<double> u = u0;
    u[started] = double(i) / points;
    // 0.01 in chi^2 is far below any decision: a small simplex within it is converged.
    stats::UnitMinimum m = held.empty()       ? stats::UnitMinimum{u, objective(u)}
                           : held.size() == 1 ? stats::golden_section(objective, u, held[0], inner)
                                              : stats::nelder_mead(objective, u, held, 0.04, 12, 0.01);
    if (m.value < best) {
      best = m.value;
      best_u = m.x;
    }
  }
  return best_u;
}

}  // namespace

ModelFit fit_model(Predictor& predictor, const ModelExtension* extension, const std::vector<char>& use,
                   const std::vector<double>& start, double step, int max_evaluations,
                   const Prediction* target) {
  const Observations& obs = predictor.observations();
  auto params = predictor.parameters(extension);
  size_t n = params.size();
  ModelFit fit;
  for (const auto& g : obs.groups) fit.groups += use[g.condition] ? 1 : 0;
  auto values = [&](const std::vector<double>& u) {
    std::vector<double> v(n);
    for (size_t k = 0; k < n; ++k) v[k] = params[k].from_unit(u[k]);
    return v;
  };
  stats::UnitObjective objective = [&](const std::vector<double>& u) {
    ++fit.evaluations;
    return chi_square(obs, predictor.predict(extension, values(u), use), use, target);
  };
  if (n == 0) {
    fit.predicted = predictor.predict(extension, {}, use);
    fit.chi2 = chi_square(obs, fit.predicted, use, target);
    return fit;
  }
  std::vector<double> u0(n, 0.5);
  for (size_t k = 0; k < n; ++k) {
    if (k < start.size()) u0[k] = std::clamp(params[k].to_unit(start[k]), 0.0, 1.0);
    else if (predictor.fits_baseline() && k == 0) u0[k] = params[0].to_unit(predictor.case_baseline_value());
  }
  if (start.size() < n) {
    u0 = profile_start(objective, u0, start.size(), predictor.expensive());
    step = std::min(step, 0.08);
  }
  if (predictor.expensive()) max_evaluations = std::min(max_evaluations, 24);
  std::vector<size_t> all_dims(n);
  for (size_t k = 0; k < n; ++k) all_dims[k] = k;
  stats::UnitMinimum best = stats::nelder_mead(objective, u0, all_dims, step, max_evaluations, 0.01);
  fit.params = values(best.x);
  fit.predicted = predictor.predict(extension, fit.params, use);  // cached
  fit.chi2 = best.value;
  return fit;
}

}  // namespace repose
