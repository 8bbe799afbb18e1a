#include "stats/calibration_curve.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "stats/errors.h"
#include "util/number_text.h"

namespace repose::stats {

namespace {

std::string num(double v) { return format_g(v, 6); }

}  // namespace

double CalibrationCurve::operator()(double x) const {
  double t = (x - centre) / scale, v = 0;
  for (Eigen::Index i = scaled.size() - 1; i >= 0; --i) v = v * t + scaled[i];
  return v;
}

double CalibrationCurve::derivative(double x) const {
  double t = (x - centre) / scale, v = 0;
  for (Eigen::Index i = scaled.size() - 1; i >= 1; --i) v = v * t + static_cast<double>(i) * scaled[i];
  return v / scale;
}

CalibrationCurve fit_curve(const std::vector<double>& x, const std::vector<double>& y, int degree) {
  if (x.size() != y.size()) throw CurveError("the sweep has " + std::to_string(x.size()) +
                                             " x values but " + std::to_string(y.size()) + " y values");
  if (degree < 1 || degree > 8) throw CurveError("the curve degree must lie between 1 and 8");
  std::vector<double> distinct = x;
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  if (static_cast<int>(distinct.size()) < degree + 1)
    throw CurveError("a degree-" + std::to_string(degree) + " curve needs at least " +
                     std::to_string(degree + 1) + " distinct swept values, got " +
                     std::to_string(distinct.size()));
  CalibrationCurve c;
  c.degree = degree;
  c.sweep_x = distinct;
  c.x_min = distinct.front();
  c.x_max = distinct.back();
  c.centre = 0.5 * (c.x_min + c.x_max);
  c.scale = 0.5 * (c.x_max - c.x_min);
  const Eigen::Index n = static_cast<Eigen::Index>(x.size());
  Eigen::MatrixXd V(n, degree + 1);
  Eigen::VectorXd Y(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    double t = (x[i] - c.centre) / c.scale, p = 1;
    for (int j = 0; j <= degree; ++j, p *= t) V(i, j) = p;
    Y[i] = y[i];
  }
  c.scaled = V.colPivHouseholderQr().solve(Y);
  double mean = Y.mean();
  double sst = (Y.array() - mean).square().sum();
  double sse = (Y - V * c.scaled).squaredNorm();
  c.r2 = sst > 0 ? 1 - sse / sst : 1;
  // Expand sum a_j ((x - c)/s)^j into powers of x for reporting.
  c.coefficients = Eigen::VectorXd::Zero(degree + 1);
  for (int j = 0; j <= degree; ++j) {
    double binom = 1;
    for (int m = 0; m <= j; ++m) {
      if (m > 0) binom = binom * (j - m + 1) / m;
      c.coefficients[m] += c.scaled[j] * binom * std::pow(-c.centre, j - m) / std::pow(c.scale, j);
    }
  }
  return c;
}

double invert(const CalibrationCurve& c, double y) {
  // Bracket every crossing of y on a fine grid, then bisect each to machine precision.
  const int cells = 4096;
  std::vector<double> roots;
  double lo_v = c(c.x_min), hi_v = lo_v;
  double xa = c.x_min, fa = c(xa) - y;
  for (int i = 1; i <= cells; ++i) {
    double xb = c.x_min + (c.x_max - c.x_min) * i / cells;
    double fb = c(xb) - y;
    lo_v = std::min(lo_v, fb + y);
    hi_v = std::max(hi_v, fb + y);
    if (fa == 0) {
      roots.push_back(xa);
    } else if ((fa < 0) != (fb < 0) && fb != 0) {
      double a = xa, b = xb, f_a = fa;
      for (int it = 0; it < 200 && b - a > 1e-15 * std::max(1.0, std::fabs(a)); ++it) {
        double m = 0.5 * (a + b), fm = c(m) - y;
        if ((fm < 0) == (f_a < 0)) {
          a = m;
          f_a = fm;
        } else {
          b = m;
        }
      }
      roots.push_back(0.5 * (a + b));
    }
    if (i == cells && fb == 0) roots.push_back(xb);
    xa = xb;
    fa = fb;
  }
  std::string range = "[";
  range.append(num(c.x_min)).append(", ").append(num(c.x_max)).append("]");
  if (roots.empty())
    throw CurveError("y = " + num(y) + " lies outside the swept range: over x in " + range +
                     " the curve spans " + num(lo_v) + " .. " + num(hi_v) +
                     "; extend the sweep rather than extrapolate");
  if (roots.size() > 1) {
    std::string list;
    for (double r : roots) list.append(list.empty() ? "" : ", ").append(num(r));
    throw CurveError("the curve is not monotone where it reaches y = " + num(y) +
                     ": it does so at x = " + list + " within " + range);
  }
  const double root = roots[0];
  // The sweep interval holding the root: the fitted curve must keep one slope sign there.
  auto hi_it = std::upper_bound(c.sweep_x.begin(), c.sweep_x.end(), root);
  double a = hi_it == c.sweep_x.begin() ? c.x_min : *(hi_it - 1);
  double b = hi_it == c.sweep_x.end() ? c.x_max : *hi_it;
  double d0 = c.derivative(root);
  const int samples = 64;
  for (int i = 0; i <= samples; ++i) {
    double x = a + (b - a) * i / samples;
    double d = c.derivative(x);
    if (d == 0 || (d < 0) != (d0 < 0) || d0 == 0)
      throw CurveError("the curve is not monotone around x = " + num(root) + " (its slope changes sign between the swept values " +
                       num(a) + " and " + num(b) + "): y = " + num(y) + " cannot be read off it");
  }
  return root;
}

}  // namespace repose::stats
