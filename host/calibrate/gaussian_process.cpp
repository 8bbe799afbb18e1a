#include "calibrate/gaussian_process.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "util/math.h"

namespace repose::calibrate {

namespace {

double kernel(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const Eigen::VectorXd& ell) {
  double s = 0;
  for (int d = 0; d < a.size(); ++d) {
    double u = (a[d] - b[d]) / ell[d];
    s += u * u;
  }
  return std::exp(-0.5 * s);
}

// Fits alpha and the Cholesky factor for given hyperparameters; returns the profiled
// log marginal likelihood (-inf when the matrix is not positive definite).
double condition(GaussianProcess& gp, const Eigen::VectorXd& y) {
  const int n = int(gp.x.rows());
  Eigen::MatrixXd k(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) k(i, j) = kernel(gp.x.row(i).transpose(), gp.x.row(j).transpose(), gp.length_scale);
  k.diagonal().array() += gp.noise_ratio + 1e-10;
  gp.chol.compute(k);
  if (gp.chol.info() != Eigen::Success) return -INFINITY;
  Eigen::VectorXd a = gp.chol.solve(y);
  double quad = y.dot(a);
  gp.signal_variance = std::max(quad / n, 1e-300);
  gp.alpha = a;
  double log_det = 0;
  Eigen::MatrixXd l = gp.chol.matrixL();
  for (int i = 0; i < n; ++i) log_det += 2 * std::log(l(i, i));
  // Profiled over the signal variance s2 = y'K^-1y / n: -n/2 log s2 - 1/2 log|K| - n/2.
  return -0.5 * n * std::log(gp.signal_variance) - 0.5 * log_det - 0.5 * n;
}

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }
double normal_pdf(double z) { return std::exp(-0.5 * z * z) / std::sqrt(2 * kPi); }

}  // namespace

GaussianProcess fit_gaussian_process(const Eigen::MatrixXd& x, const Eigen::VectorXd& y) {
  const int n = int(x.rows()), k = int(x.cols());
  if (n < 2) throw std::runtime_error("a Gaussian process needs at least two runs");
  GaussianProcess best;
  best.x = x;
  best.y_mean = y.mean();
  double var = (y.array() - best.y_mean).square().sum() / n;
  best.y_scale = var > 0 ? std::sqrt(var) : 1.0;
  Eigen::VectorXd ys = (y.array() - best.y_mean) / best.y_scale;

  // Length scales 0.1 .. 10 coded units (log grid), each factor its own up to 3 factors, one
  // shared beyond (the grid would grow as 13^k); nugget ratios from noise-free to noisy.
  std::vector<double> scales;
  for (int i = 0; i < 13; ++i) scales.push_back(0.1 * std::pow(100.0, i / 12.0));
  const std::vector<double> nuggets = {1e-8, 1e-6, 1e-4, 1e-3, 1e-2, 1e-1};
  const bool per_factor = k <= 3;
  long combos = 1;
  for (int d = 0; d < (per_factor ? k : 1); ++d) combos *= long(scales.size());
  best.log_likelihood = -INFINITY;
  GaussianProcess trial = best;
  trial.length_scale.resize(k);
  for (double nugget : nuggets)
    for (long c = 0; c < combos; ++c) {
      long code = c;
      for (int d = 0; d < k; ++d) {
        if (per_factor || d == 0) {
          trial.length_scale[d] = scales[code % scales.size()];
          code /= long(scales.size());
        } else trial.length_scale[d] = trial.length_scale[0];
      }
      trial.noise_ratio = nugget;
      double ll = condition(trial, ys);
      if (ll > best.log_likelihood + 1e-9) {
        trial.log_likelihood = ll;
        best = trial;
      }
    }
  if (!std::isfinite(best.log_likelihood)) throw std::runtime_error("Gaussian process: no hyperparameters fit the runs");
  return best;
}

double GaussianProcess::mean(const Eigen::VectorXd& at) const {
  double m = 0;
  for (int i = 0; i < x.rows(); ++i) m += kernel(at, x.row(i).transpose(), length_scale) * alpha[i];
  return y_mean + y_scale * m;
}

double GaussianProcess::sd(const Eigen::VectorXd& at) const {
  Eigen::VectorXd c(x.rows());
  for (int i = 0; i < x.rows(); ++i) c[i] = kernel(at, x.row(i).transpose(), length_scale);
  double v = 1.0 - c.dot(chol.solve(c));
  return y_scale * std::sqrt(std::max(0.0, signal_variance * v));
}

Eigen::VectorXd GaussianProcess::gradient(const Eigen::VectorXd& at) const {
  Eigen::VectorXd g(at.size());
  const double h = 1e-4;
  for (int d = 0; d < at.size(); ++d) {
    Eigen::VectorXd p = at, m = at;
    p[d] += h;
    m[d] -= h;
    g[d] = (mean(p) - mean(m)) / (2 * h);
  }
  return g;
}

double expected_improvement_to_target(double mean, double sd, double target, double best) {
  const double m = mean - target, b = best;
  if (!(sd > 0)) return std::max(0.0, b - std::abs(m));
  // Z = Y - target ~ N(m, sd^2); EI = integral over -b..b of (b - |z|) p(z) dz, split at 0,
  // using  integral_a^c z p(z) dz = m [Phi(c') - Phi(a')] + sd [phi(a') - phi(c')].
  auto z = [&](double v) { return (v - m) / sd; };
  const double zb = z(b), z0 = z(0), zmb = z(-b);
  const double mass = normal_cdf(zb) - normal_cdf(zmb);
  const double upper = m * (normal_cdf(zb) - normal_cdf(z0)) + sd * (normal_pdf(z0) - normal_pdf(zb));
  const double lower = m * (normal_cdf(z0) - normal_cdf(zmb)) + sd * (normal_pdf(zmb) - normal_pdf(z0));
  return std::max(0.0, b * mass - upper + lower);
}

}  // namespace repose::calibrate
