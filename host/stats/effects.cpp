#include "stats/effects.h"

#include <algorithm>
#include <cmath>

#include "stats/errors.h"
#include "stats/fdist.h"
#include "stats/model_terms.h"

namespace repose::stats {

std::vector<Effect> standardised_effects(const ResponseSurface& fit, const std::vector<std::string>& factor_names) {
  if (fit.residual.df <= 0)
    throw StatsError("standardised effects need residual degrees of freedom (the model uses every run)");
  std::vector<Effect> effects;
  for (size_t k = 0; k < fit.terms.size(); ++k) {
    if (fit.terms[k].is_intercept()) continue;
    const Coefficient& c = fit.coefficients[k];
    effects.push_back({term_name(fit.terms[k], factor_names), c.estimate, 2 * c.estimate,
                       c.std_error > 0 ? c.estimate / c.std_error : 0});
  }
  std::stable_sort(effects.begin(), effects.end(),
                   [](const Effect& a, const Effect& b) { return std::abs(a.t) > std::abs(b.t); });
  return effects;
}

double t_value_limit(double alpha, int df) { return std::sqrt(f_critical(alpha, 1, df)); }

double bonferroni_limit(double alpha, int m, int df) { return t_value_limit(alpha / std::max(1, m), df); }

double normal_quantile(double p) {
  double lo = -40, hi = 40;
  for (int i = 0; i < 200 && hi - lo > 1e-13; ++i) {
    double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::vector<double> half_normal_quantiles(int m) {
  std::vector<double> q;
  for (int i = 1; i <= m; ++i) q.push_back(normal_quantile(0.5 + 0.5 * (i - 0.5) / m));
  return q;
}

}  // namespace repose::stats
