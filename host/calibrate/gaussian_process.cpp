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

// Fits alpha and the Cholesky factor for the process's hyperparameters.
bool condition(GaussianProcess& gp, const Eigen::VectorXd& y) {
  const int n = int(gp.x.rows());
  Eigen::MatrixXd k(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) k(i, j) = kernel(gp.x.row(i).transpose(), gp.x.row(j).transpose(), gp.length_scale);
  k.diagonal().array() += gp.noise_ratio + 1e-10;
  gp.chol.compute(k);
  if (gp.chol.info() != Eigen::Success) return false;
  gp.alpha = gp.chol.solve(y);
  return true;
}

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }
double normal_pdf(double z) { return std::exp(-0.5 * z * z) / std::sqrt(2 * kPi); }

// The best signal and noise variances for one kernel matrix R = Q diag(lambda) Q' and the
// standardised response (z = Q'y): K = s2 R + v I, log likelihood -1/2 sum z^2 / (s2 lambda + v)
// - 1/2 sum log(s2 lambda + v) (constants dropped). Over noise/signal ratios r on a log grid,
// s2 is profiled (s2 = sum z^2 / (lambda + r) / n); where the implied noise v = s2 r leaves the
// bounds, v is put on the bound instead (s2 = v / r), which walks the bound line.
struct VarianceChoice {
  double log_likelihood = -INFINITY, signal = 1, ratio = 1e-8;
};
VarianceChoice best_variances(const Eigen::VectorXd& lambda, const Eigen::VectorXd& z, double v_low, double v_high) {
  const int n = int(z.size());
  VarianceChoice best;
  for (int g = 0; g <= 40; ++g) {
    const double r = std::pow(10.0, -8.0 + 0.25 * g);  // 1e-8 .. 1e2
    double s2 = 0;
    for (int i = 0; i < n; ++i) s2 += z[i] * z[i] / (std::max(lambda[i], 0.0) + r + 1e-10);
    s2 = std::max(s2 / n, 1e-300);
    double v = s2 * r;
    if (v < v_low) v = v_low, s2 = v / r;
    if (v > v_high) v = v_high, s2 = v / r;
    double ll = 0;
    for (int i = 0; i < n; ++i) {
      const double e = s2 * (std::max(lambda[i], 0.0) + 1e-10) + v;
      ll -= 0.5 * (z[i] * z[i] / e + std::log(e));
    }
    if (ll > best.log_likelihood + 1e-9) best = {ll, s2, v / s2};
  }
  return best;
}

}  // namespace

GaussianProcess fit_gaussian_process(const Eigen::MatrixXd& x, const Eigen::VectorXd& y, const NoiseBounds& noise) {
  const int n = int(x.rows()), k = int(x.cols());
  if (n < 2) throw std::runtime_error("a Gaussian process needs at least two runs");
  GaussianProcess best;
  best.x = x;
  best.y_mean = y.mean();
  double var = (y.array() - best.y_mean).square().sum() / n;
  best.y_scale = var > 0 ? std::sqrt(var) : 1.0;
  Eigen::VectorXd ys = (y.array() - best.y_mean) / best.y_scale;
  // The noise bounds as variances of the standardised response.
  const double v_low = std::pow(noise.low / best.y_scale, 2), v_high = std::pow(noise.high / best.y_scale, 2);

  // Length scales 0.1 .. 10 coded units (log grid), each factor its own up to 3 factors, one
  // shared beyond (the grid would grow as 13^k).
  std::vector<double> scales;
  for (int i = 0; i < 13; ++i) scales.push_back(0.1 * std::pow(100.0, i / 12.0));
  const bool per_factor = k <= 3;
  long combos = 1;
  for (int d = 0; d < (per_factor ? k : 1); ++d) combos *= long(scales.size());
  best.log_likelihood = -INFINITY;
  Eigen::VectorXd ell(k);
  Eigen::MatrixXd r(n, n);
  for (long c = 0; c < combos; ++c) {
    long code = c;
    for (int d = 0; d < k; ++d) {
      if (per_factor || d == 0) {
        ell[d] = scales[size_t(code % long(scales.size()))];
        code /= long(scales.size());
      } else ell[d] = ell[0];
    }
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) r(i, j) = kernel(x.row(i).transpose(), x.row(j).transpose(), ell);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(r);
    if (eigen.info() != Eigen::Success) continue;
    const Eigen::VectorXd z = eigen.eigenvectors().transpose() * ys;
    VarianceChoice v = best_variances(eigen.eigenvalues(), z, v_low, v_high);
    if (v.log_likelihood > best.log_likelihood + 1e-9) {
      best.log_likelihood = v.log_likelihood;
      best.length_scale = ell;
      best.signal_variance = v.signal;
      best.noise_ratio = v.ratio;
    }
  }
  if (!std::isfinite(best.log_likelihood) || !condition(best, ys))
    throw std::runtime_error("Gaussian process: no hyperparameters fit the runs");
  return best;
}

double GaussianProcess::noise_sd() const { return y_scale * std::sqrt(signal_variance * noise_ratio); }

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
