#include "diagnosis/model_fit.h"

#include <algorithm>
#include <cmath>

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

}  // namespace repose
