// Calibration curves: one parameter swept in simulation, a polynomial (cubic by default) fitted
// to (parameter, response), then inverted at the measured response. Inversion refuses to
// extrapolate beyond the sweep and refuses a curve that is not monotone where it would be read.
#pragma once
#include <Eigen/Dense>
#include <vector>

namespace repose::stats {

struct CalibrationCurve {
  int degree = 3;
  double x_min = 0, x_max = 0;  // the swept range
  std::vector<double> sweep_x;  // distinct swept values, ascending
  double r2 = 0;
  Eigen::VectorXd coefficients;  // in powers of x, ascending (c0 + c1 x + c2 x^2 + ...)

  double operator()(double x) const;
  double derivative(double x) const;

  // Evaluation uses the scaled variable t = (x - centre) / scale, which keeps a cubic over
  // 0.04..0.06 well conditioned; `coefficients` is the same polynomial expanded in x.
  double centre = 0, scale = 1;
  Eigen::VectorXd scaled;  // in powers of t, ascending
};

// Least squares fit; throws CurveError with fewer distinct x values than degree + 1.
CalibrationCurve fit_curve(const std::vector<double>& x, const std::vector<double>& y, int degree = 3);

// The x in the swept range where the curve equals y. Throws CurveError when y lies outside
// the curve's values over the swept range, when y is reached more than once, or when the
// curve turns (its slope changes sign or vanishes) within the sweep interval holding the root.
double invert(const CalibrationCurve& curve, double y);

}  // namespace repose::stats
