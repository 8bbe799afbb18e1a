// The F distribution's upper tail from the regularised incomplete beta function, checked
// against closed forms and against printed critical values (e.g. Montgomery, Table IV).
#include <catch2/catch.hpp>

#include <cmath>

#include "stats/fdist.h"
#include "util/math.h"

using namespace repose::stats;

TEST_CASE("incomplete beta: closed forms and symmetry", "[stats][fdist]") {
  for (double x : {0.0, 0.01, 0.2, 0.5, 0.77, 0.999, 1.0}) {
    CHECK(regularized_incomplete_beta(1, 1, x) == Approx(x).margin(1e-14));
    CHECK(regularized_incomplete_beta(3.5, 1, x) == Approx(std::pow(x, 3.5)).margin(1e-14));
    CHECK(regularized_incomplete_beta(1, 2.5, x) == Approx(1 - std::pow(1 - x, 2.5)).margin(1e-14));
    for (double a : {0.5, 2.0, 7.5})
      for (double b : {0.5, 3.0, 40.0})
        CHECK(regularized_incomplete_beta(a, b, x) ==
              Approx(1 - regularized_incomplete_beta(b, a, 1 - x)).margin(1e-13));
  }
  CHECK(regularized_incomplete_beta(4.2, 4.2, 0.5) == Approx(0.5).margin(1e-14));
  // I_x(1/2, 1/2) = (2/pi) asin(sqrt(x)).
  CHECK(regularized_incomplete_beta(0.5, 0.5, 0.3) ==
        Approx(2 / repose::kPi * std::asin(std::sqrt(0.3))).margin(1e-13));
  CHECK_THROWS(regularized_incomplete_beta(0, 1, 0.5));
  CHECK_THROWS(regularized_incomplete_beta(1, 1, 1.5));
}

TEST_CASE("F upper tail: closed form for d1 = 2 and printed critical values", "[stats][fdist]") {
  // P(F(2, d2) > f) = (1 + 2 f / d2)^(-d2 / 2).
  for (double d2 : {1.0, 5.0, 10.0, 37.0})
    for (double f : {0.1, 1.0, 4.0, 30.0})
      CHECK(f_upper_tail(f, 2, d2) == Approx(std::pow(1 + 2 * f / d2, -d2 / 2)).epsilon(1e-12));
  // Critical values F_{alpha}(d1, d2) as tabulated (4-5 significant digits).
  CHECK(f_upper_tail(4.96, 1, 10) == Approx(0.05).margin(2e-4));
  CHECK(f_upper_tail(5.32, 1, 8) == Approx(0.05).margin(2e-4));
  CHECK(f_upper_tail(5.05, 5, 5) == Approx(0.05).margin(2e-4));
  CHECK(f_upper_tail(3.02, 9, 10) == Approx(0.05).margin(2e-4));
  CHECK(f_upper_tail(4.94, 9, 10) == Approx(0.01).margin(1e-4));
  CHECK(f_upper_tail(10.04, 1, 10) == Approx(0.01).margin(1e-4));
  CHECK(f_critical(0.05, 1, 10) == Approx(4.9646).margin(1e-4));
  CHECK(f_critical(0.05, 5, 5) == Approx(5.0503).margin(1e-4));
  CHECK(f_upper_tail(0, 3, 4) == 1);
  CHECK(f_upper_tail(-1, 3, 4) == 1);
  CHECK(std::isnan(f_upper_tail(1, 0, 4)));
  // Large degrees of freedom stay accurate: F(200, 200) is nearly symmetric about 1.
  CHECK(f_upper_tail(1.0, 200, 200) == Approx(0.5).margin(1e-10));
}

TEST_CASE("chi-square: closed forms and printed quantiles", "[stats][fdist]") {
  // df = 2: P(X <= x) = 1 - exp(-x / 2); df = 1: erf(sqrt(x / 2)).
  for (double x : {0.01, 0.5, 2.0, 7.0, 40.0}) {
    CHECK(chi_square_cdf(x, 2) == Approx(1 - std::exp(-x / 2)).epsilon(1e-12));
    CHECK(chi_square_cdf(x, 1) == Approx(std::erf(std::sqrt(x / 2))).epsilon(1e-12));
  }
  // Tabulated quantiles (4 decimals): 0.025 and 0.975 at 3, 9 and 30 df.
  CHECK(chi_square_quantile(0.025, 3) == Approx(0.2158).margin(1e-4));
  CHECK(chi_square_quantile(0.975, 3) == Approx(9.3484).margin(1e-4));
  CHECK(chi_square_quantile(0.025, 9) == Approx(2.7004).margin(1e-4));
  CHECK(chi_square_quantile(0.975, 9) == Approx(19.0228).margin(1e-4));
  CHECK(chi_square_quantile(0.975, 30) == Approx(46.9792).margin(1e-4));
  CHECK(chi_square_cdf(0, 4) == 0);
}
