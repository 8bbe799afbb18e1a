#include "stats/fdist.h"

#include <cmath>
#include <limits>

#include "stats/errors.h"

namespace repose::stats {

namespace {

// Continued fraction for I_x(a,b) (Numerical Recipes 6.4, modified Lentz). Converges quickly
// for x < (a+1)/(a+b+2); the caller uses the symmetry I_x(a,b) = 1 - I_{1-x}(b,a) otherwise.
double beta_continued_fraction(double a, double b, double x) {
  const double tiny = 1e-300;
  const double eps = 1e-15;
  double qab = a + b, qap = a + 1.0, qam = a - 1.0;
  double c = 1.0;
  double d = 1.0 - qab * x / qap;
  if (std::fabs(d) < tiny) d = tiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m <= 10000; ++m) {
    double m2 = 2.0 * m;
    double aa = m * (b - m) * x / ((qam + m2) * (a + m2));  // even step
    d = 1.0 + aa * d;
    if (std::fabs(d) < tiny) d = tiny;
    c = 1.0 + aa / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    h *= d * c;
    aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));  // odd step
    d = 1.0 + aa * d;
    if (std::fabs(d) < tiny) d = tiny;
    c = 1.0 + aa / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    double del = d * c;
    h *= del;
    if (std::fabs(del - 1.0) < eps) return h;
  }
  throw StatsError("incomplete beta: continued fraction did not converge (a=" + std::to_string(a) +
                   ", b=" + std::to_string(b) + ", x=" + std::to_string(x) + ")");
}

}  // namespace

double regularized_incomplete_beta(double a, double b, double x) {
  if (!(a > 0) || !(b > 0)) throw StatsError("incomplete beta: a and b must be positive");
  if (!(x >= 0 && x <= 1)) throw StatsError("incomplete beta: x must lie in [0, 1]");
  if (x == 0) return 0;
  if (x == 1) return 1;
  // Prefactor x^a (1-x)^b / (a B(a,b)), in logs to avoid overflow for large a, b.
  double ln_front = std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) +
                    b * std::log1p(-x);
  double front = std::exp(ln_front);
  if (x < (a + 1.0) / (a + b + 2.0)) return front * beta_continued_fraction(a, b, x) / a;
  return 1.0 - front * beta_continued_fraction(b, a, 1.0 - x) / b;
}

double f_upper_tail(double f, double d1, double d2) {
  if (!(d1 > 0) || !(d2 > 0)) return std::numeric_limits<double>::quiet_NaN();
  if (std::isnan(f)) return f;
  if (f <= 0) return 1.0;
  if (std::isinf(f)) return 0.0;
  // P(F > f) = I_{d2/(d2 + d1 f)}(d2/2, d1/2)
  return regularized_incomplete_beta(0.5 * d2, 0.5 * d1, d2 / (d2 + d1 * f));
}

double f_critical(double p, double d1, double d2) {
  if (!(p > 0 && p < 1)) throw StatsError("f_critical: p must lie in (0, 1)");
  double lo = 0, hi = 1;
  while (f_upper_tail(hi, d1, d2) > p) hi *= 2;
  for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i) {
    double mid = 0.5 * (lo + hi);
    (f_upper_tail(mid, d1, d2) > p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

namespace {

// Series for P(a, x), good for x < a + 1 (Numerical Recipes 6.2).
double gamma_series(double a, double x) {
  double sum = 1.0 / a, term = sum;
  for (int n = 1; n <= 10000; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::fabs(term) < std::fabs(sum) * 1e-16) return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
  }
  throw StatsError("incomplete gamma: series did not converge (a=" + std::to_string(a) + ", x=" + std::to_string(x) + ")");
}

// Continued fraction for Q(a, x) = 1 - P(a, x), good for x >= a + 1 (modified Lentz).
double gamma_continued_fraction(double a, double x) {
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i <= 10000; ++i) {
    double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::fabs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    double del = d * c;
    h *= del;
    if (std::fabs(del - 1.0) < 1e-15) return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
  }
  throw StatsError("incomplete gamma: continued fraction did not converge (a=" + std::to_string(a) + ", x=" +
                   std::to_string(x) + ")");
}

}  // namespace

double regularized_lower_gamma(double a, double x) {
  if (!(a > 0)) throw StatsError("incomplete gamma: a must be positive");
  if (!(x > 0)) return 0;
  if (std::isinf(x)) return 1;
  return x < a + 1.0 ? gamma_series(a, x) : 1.0 - gamma_continued_fraction(a, x);
}

double chi_square_cdf(double x, double df) { return regularized_lower_gamma(0.5 * df, 0.5 * x); }

double chi_square_quantile(double p, double df) {
  if (!(p > 0 && p < 1)) throw StatsError("chi_square_quantile: p must lie in (0, 1)");
  if (!(df > 0)) throw StatsError("chi_square_quantile: df must be positive");
  double lo = 0, hi = df + 10;
  while (chi_square_cdf(hi, df) < p) hi *= 2;
  for (int i = 0; i < 200 && hi - lo > 1e-13 * hi; ++i) {
    double mid = 0.5 * (lo + hi);
    (chi_square_cdf(mid, df) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace repose::stats
