// The F distribution's upper tail, the p value of an ANOVA F test, and the chi-square
// distribution (a replicate variance's confidence interval). Computed from the regularised
// incomplete beta and gamma functions (series and continued fractions, modified Lentz), so the
// library needs nothing beyond the C++ standard library and Eigen.
#pragma once

namespace repose::stats {

// I_x(a, b) = B(x; a, b) / B(a, b), for a, b > 0 and 0 <= x <= 1. Accurate to ~1e-14.
double regularized_incomplete_beta(double a, double b, double x);

// P(F > f) for F ~ F(d1, d2). f <= 0 gives 1.
double f_upper_tail(double f, double d1, double d2);

// The value f with P(F > f) = p (bisection on f_upper_tail; used for critical values).
double f_critical(double p, double d1, double d2);

// P(a, x) = gamma(a, x) / Gamma(a), the regularised lower incomplete gamma function (a > 0).
double regularized_lower_gamma(double a, double x);

// P(X <= x) for X ~ chi-square with `df` degrees of freedom, and its inverse (bisection).
double chi_square_cdf(double x, double df);
double chi_square_quantile(double p, double df);

}  // namespace repose::stats
