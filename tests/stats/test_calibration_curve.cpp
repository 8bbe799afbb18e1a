// Calibration curves from the cabbage study (section 3.1): a contact parameter swept in EDEM,
// a cubic fitted to the response, inverted at the physically measured value. The paper gives
// the cubics (Eqs. 4-6) and the sweeps (restitution and static friction 0.1..0.9 by 0.1,
// rolling friction 0.04..0.06 by 0.0025); the sweep responses are regenerated from the printed
// cubics, refitted, and inverted at the measured values of Tables 4-6.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <string>

#include "stats/calibration_curve.h"
#include "stats/errors.h"

using namespace repose::stats;

namespace {

struct PrintedCubic {
  const char* name;
  double c3, c2, c1, c0;     // as printed
  double lo, hi, step;       // the sweep of section 3.1
  double measured;           // Table 4, 5 or 6
  double paper;              // the calibrated value the paper reports
  double paper_half_unit;    // half a unit of the paper's last printed digit
};

CalibrationCurve refit(const PrintedCubic& e) {
  std::vector<double> x, y;
  int n = static_cast<int>(std::lround((e.hi - e.lo) / e.step));
  for (int i = 0; i <= n; ++i) {
    double v = e.lo + i * e.step;
    x.push_back(v);
    y.push_back(((e.c3 * v + e.c2) * v + e.c1) * v + e.c0);
  }
  CalibrationCurve c = fit_curve(x, y);
  // The refit is the printed cubic itself.
  CHECK(c.r2 == Approx(1.0).margin(1e-12));
  CHECK(c.coefficients[3] == Approx(e.c3).epsilon(1e-6));
  CHECK(c.coefficients[0] == Approx(e.c0).epsilon(1e-6).margin(1e-6));
  return c;
}

double check_inversion(const PrintedCubic& e) {
  CalibrationCurve c = refit(e);
  double x = invert(c, e.measured);
  char line[200];
  std::snprintf(line, sizeof line, "%s at %.2f: curve gives %.5f, paper reports %g", e.name,
                e.measured, x, e.paper);
  INFO(line);
  CHECK(c(x) == Approx(e.measured).epsilon(1e-10));
  return x;
}

}  // namespace

TEST_CASE("cabbage Eq. 4: restitution from the Table 4 rebound heights", "[stats][curve]") {
  const PrintedCubic eqs[] = {
      {"h1 steel", -3.55892, 504.58092, -8.0706, 2.8031, 0.1, 0.9, 0.1, 93.80, 0.43, 0.005},
      {"h2 PVC", -46.9167, 554.55823, -17.24406, 5.212626, 0.1, 0.9, 0.1, 100.10, 0.44, 0.005},
      {"h3 EVA", 265.37963, 184.48499, 51.28399, 4.81823, 0.1, 0.9, 0.1, 134.82, 0.55, 0.005},
      {"h4 wood", -0.378704, 505.1864, -8.46492, 2.88952, 0.1, 0.9, 0.1, 82.21, 0.41, 0.005},
  };
  for (int i = 0; i < 3; ++i) {
    double x = check_inversion(eqs[i]);
    CHECK(std::fabs(x - eqs[i].paper) <= eqs[i].paper_half_unit);
  }
  // Finding: wood. Eq. 4 reaches the measured 82.21 mm at e = 0.4048, which rounds to 0.40;
  // the paper calibrates 0.41 (the directly measured Table 4 value), where Eq. 4 gives
  // 84.31 mm (its own simulation at 0.41 gave 84.02 mm, 2.2 % above the measurement).
  double wood = check_inversion(eqs[3]);
  CHECK(wood == Approx(0.40478).margin(0.00005));
  CHECK(refit(eqs[3])(0.41) == Approx(84.31).margin(0.01));
}

TEST_CASE("cabbage Eq. 5: static friction from the Table 5 sliding angles", "[stats][curve]") {
  const PrintedCubic eqs[] = {
      {"alpha1 steel", -16.7687, 13.83309, 45.26707, 3.27797, 0.1, 0.9, 0.1, 35.31, 0.67, 0.005},
      {"alpha2 PVC", 23.78017, -53.13228, 77.50156, -1.07403, 0.1, 0.9, 0.1, 20.24, 0.34, 0.005},
      {"alpha3 EVA", 12.89455, -39.25649, 74.05492, -1.11075, 0.1, 0.9, 0.1, 37.17, 0.73, 0.005},
      {"alpha4 wood", -0.77338, -13.78027, 59.20023, 1.39223, 0.1, 0.9, 0.1, 33.82, 0.65, 0.005},
  };
  for (int i = 1; i < 4; ++i) {
    double x = check_inversion(eqs[i]);
    CHECK(std::fabs(x - eqs[i].paper) <= eqs[i].paper_half_unit);
  }
  // Finding: steel. Eq. 5 reaches the measured 35.31 deg at mu_s = 0.6831 (0.68); the paper
  // calibrates 0.67, where Eq. 5 gives 34.77 deg (its own simulation at 0.67 gave 35.21 deg).
  double steel = check_inversion(eqs[0]);
  CHECK(steel == Approx(0.68311).margin(0.00005));
  CHECK(refit(eqs[0])(0.67) == Approx(34.77).margin(0.01));
}

TEST_CASE("cabbage Eq. 6: rolling friction from the Table 6 rolling distances", "[stats][curve]") {
  // Finding: the paper's text under Eq. 6 repeats the static friction values "0.67, 0.34,
  // 0.73 and 0.65" (copied from Eq. 5). The inversion gives the final calibrated values
  // 0.0476, 0.0478, 0.0486 and 0.0517 that the paper states at the end of the section.
  const PrintedCubic eqs[] = {
      {"L1 steel", -7811447.8111, 1586262.62621, -117664.30976, 3531.05051, 0.04, 0.06, 0.0025, 682.6, 0.0476, 0.00005},
      {"L2 PVC", -9373737.37335, 1778874.45882, -125219.76912, 3619.20779, 0.04, 0.06, 0.0025, 673.8, 0.0478, 0.00005},
      {"L3 EVA", -5925925.92525, 1281269.84117, -101578.83597, 3244.93651, 0.04, 0.06, 0.0025, 653.8, 0.0486, 0.00005},
      {"L4 wood", 1346801.34807, 206810.96662, -48381.43337, 2349.32612, 0.04, 0.06, 0.0025, 586.9, 0.0517, 0.00005},
  };
  const double got[] = {0.047562, 0.047830, 0.048625, 0.051700};
  for (int i = 0; i < 4; ++i) {
    double x = check_inversion(eqs[i]);
    CHECK(std::fabs(x - eqs[i].paper) <= eqs[i].paper_half_unit);
    CHECK(x == Approx(got[i]).margin(0.000001));
    CHECK(std::fabs(x - 0.67) > 0.5);  // nothing like the text's copied values
  }
}

TEST_CASE("calibration curve: refuses to extrapolate or to read a turning curve", "[stats][curve]") {
  // Outside the swept range.
  std::vector<double> x = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9}, y;
  for (double v : x) y.push_back(500 * v * v);
  CalibrationCurve c = fit_curve(x, y);
  CHECK(invert(c, 125) == Approx(0.5).epsilon(1e-9));
  CHECK_THROWS_AS(invert(c, 450), CurveError);
  CHECK_THROWS_WITH(invert(c, 450), Catch::Contains("outside the swept range"));
  CHECK_THROWS_WITH(invert(c, 1), Catch::Contains("outside the swept range"));

  // Reached twice: y = (x - 0.5)^2 over 0..1.
  std::vector<double> xs = {0, 0.25, 0.5, 0.75, 1}, ys;
  for (double v : xs) ys.push_back((v - 0.5) * (v - 0.5));
  CalibrationCurve parabola = fit_curve(xs, ys, 2);
  CHECK_THROWS_WITH(invert(parabola, 0.1), Catch::Contains("not monotone"));

  // Reached once, but the curve turns inside the sweep interval holding the root:
  // y = x^3 - 0.3 x over 0.25..1 has its minimum at 0.316, between the swept 0.25 and 0.5.
  std::vector<double> xt = {0.25, 0.5, 0.75, 1}, yt;
  for (double v : xt) yt.push_back(v * v * v - 0.3 * v);
  CalibrationCurve turning = fit_curve(xt, yt);
  CHECK_THROWS_WITH(invert(turning, -0.05), Catch::Contains("not monotone around"));
  CHECK(invert(turning, 0.4) == Approx(0.87126).margin(0.0001));  // a monotone stretch is fine

  // Too few swept values for the degree.
  CHECK_THROWS_AS(fit_curve({0.1, 0.2, 0.3}, {1, 2, 3}, 3), CurveError);
}
