// Design-Expert's screening views of a fitted two-level model (a Plackett-Burman or factorial
// screening): each term's standardised effect t = coefficient / its standard error (the Pareto
// chart ranks |t| against the t-value and Bonferroni limits), and its effect, twice the
// coefficient in coded units (the half-normal plot puts |effect| against half-normal quantiles:
// effects that are noise fall on a line through the origin, real ones stand off it).
#pragma once
#include <string>
#include <vector>

#include "stats/anova.h"

namespace repose::stats {

struct Effect {
  std::string term;        // with factor names ("mu_s", "mu_s*mu_r")
  double coefficient = 0;  // coded units
  double effect = 0;       // 2 x coefficient: the response's change from -1 to +1
  double t = 0;            // coefficient / standard error
};

// Every non-intercept term, largest |t| first. Throws StatsError when the fit has no residual
// degrees of freedom (no standard errors).
std::vector<Effect> standardised_effects(const ResponseSurface& fit, const std::vector<std::string>& factor_names);

// |t| above which an effect is significant at `alpha` (two-sided, residual df), and the
// Bonferroni limit for `m` effects tested together (alpha / m).
double t_value_limit(double alpha, int df);
double bonferroni_limit(double alpha, int m, int df);

// The standard normal quantile (bisection on erfc: host-side, to 1e-12).
double normal_quantile(double p);
// The half-normal quantiles of m ordered absolute effects: Phi^-1(0.5 + 0.5 (i - 0.5) / m).
std::vector<double> half_normal_quantiles(int m);

}  // namespace repose::stats
