// The F distribution's upper tail, the p value of an ANOVA F test. Computed from the
// regularised incomplete beta function (continued fraction, modified Lentz), so the library
// needs nothing beyond the C++ standard library and Eigen.
#pragma once

namespace repose::stats {

// I_x(a, b) = B(x; a, b) / B(a, b), for a, b > 0 and 0 <= x <= 1. Accurate to ~1e-14.
double regularized_incomplete_beta(double a, double b, double x);

// P(F > f) for F ~ F(d1, d2). f <= 0 gives 1.
double f_upper_tail(double f, double d1, double d2);

// The value f with P(F > f) = p (bisection on f_upper_tail; used for critical values).
double f_critical(double p, double d1, double d2);

}  // namespace repose::stats
