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

// The trend's basis at every training point, one row each.
Eigen::MatrixXd basis_matrix(const GaussianProcess& gp) {
  Eigen::MatrixXd h(gp.x.rows(), gp.trend ? gp.x.cols() + 1 : 1);
  for (int i = 0; i < gp.x.rows(); ++i) h.row(i) = gp.basis(gp.x.row(i).transpose()).transpose();
  return h;
}

// Fits the trend, alpha and the factors prediction needs, for the process's hyperparameters.
bool condition(GaussianProcess& gp, const Eigen::VectorXd& y) {
  const int n = int(gp.x.rows());
  Eigen::MatrixXd k(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) k(i, j) = kernel(gp.x.row(i).transpose(), gp.x.row(j).transpose(), gp.length_scale);
  k.diagonal().array() += gp.noise_ratio + 1e-10;
  gp.chol.compute(k);
  if (gp.chol.info() != Eigen::Success) return false;
  gp.h = basis_matrix(gp);
  const Eigen::MatrixXd kinv_h = gp.chol.solve(gp.h);
  gp.h_kinv_h_inverse = (gp.h.transpose() * kinv_h).inverse();
  gp.beta = gp.h_kinv_h_inverse * (kinv_h.transpose() * y);
  gp.alpha = gp.chol.solve(y - gp.h * gp.beta);
  return true;
}

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }
double normal_pdf(double z) { return std::exp(-0.5 * z * z) / std::sqrt(2 * kPi); }

// The best signal and noise variances for one kernel matrix R = Q diag(lambda) Q', the
// standardised response (z = Q'y) and the trend's basis (g = Q'H): K = s2 (R + r I) with the
// noise v = s2 r. The restricted log likelihood, constants dropped, is
//   -1/2 [(n - p) log s2 + sum log(lambda + r) + log|A| + q / s2],
// A = g' D g, q = z' D z - b' A^-1 b, b = g' D z, D = diag(1 / (lambda + r)). Over ratios r on a
// log grid s2 is profiled (s2 = q / (n - p)); where the implied noise leaves the bounds it is put
// on the bound (s2 = v / r), which walks the bound line.
struct VarianceChoice {
  double log_likelihood = -INFINITY, signal = 1, ratio = 1e-8;
};
void variance_choices(const Eigen::VectorXd& lambda, const Eigen::VectorXd& z, const Eigen::MatrixXd& g, double v_low,
                      double v_high, std::vector<VarianceChoice>& out) {
  const int n = int(z.size()), p = int(g.cols());
  Eigen::VectorXd d(n);
  for (int step = 0; step <= 40; ++step) {
    const double r = std::pow(10.0, -8.0 + 0.25 * step);  // 1e-8 .. 1e2
    double log_det = 0;
    for (int i = 0; i < n; ++i) {
      const double e = std::max(lambda[i], 0.0) + r + 1e-10;
      d[i] = 1 / e;
      log_det += std::log(e);
    }
    const Eigen::MatrixXd a = g.transpose() * d.asDiagonal() * g;
    const Eigen::VectorXd b = g.transpose() * d.cwiseProduct(z);
    const Eigen::LDLT<Eigen::MatrixXd> a_ldlt(a);
    const double q = std::max(z.dot(d.cwiseProduct(z)) - b.dot(a_ldlt.solve(b)), 1e-300);
    double s2 = q / (n - p);
    double v = s2 * r;
    if (v < v_low) v = v_low, s2 = v / r;
    if (v > v_high) v = v_high, s2 = v / r;
    const double ll = -0.5 * ((n - p) * std::log(s2) + log_det + a_ldlt.vectorD().array().abs().log().sum() + q / s2);
    if (std::isfinite(ll)) out.push_back({ll, s2, v / s2});
  }
}

struct Candidate {
  Eigen::VectorXd length_scale;
  VarianceChoice v;
};

// Every grid point of the hyperparameters with its restricted log likelihood.
std::vector<Candidate> candidates(const Eigen::MatrixXd& x, const Eigen::VectorXd& ys, const Eigen::MatrixXd& h, double v_low,
                                  double v_high) {
  const int n = int(x.rows()), k = int(x.cols());
  // Length scales 0.1 .. 10 coded units (log grid), each factor its own up to 3 factors, one
  // shared beyond (the grid would grow as 13^k).
  std::vector<double> scales;
  for (int i = 0; i < 13; ++i) scales.push_back(0.1 * std::pow(100.0, i / 12.0));
  const bool per_factor = k <= 3;
  long combos = 1;
  for (int d = 0; d < (per_factor ? k : 1); ++d) combos *= long(scales.size());
  std::vector<Candidate> out;
  Eigen::VectorXd ell(k);
  Eigen::MatrixXd r(n, n);
  std::vector<VarianceChoice> choices;
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
    choices.clear();
    variance_choices(eigen.eigenvalues(), eigen.eigenvectors().transpose() * ys, eigen.eigenvectors().transpose() * h, v_low,
                     v_high, choices);
    for (const auto& v : choices) out.push_back({ell, v});
  }
  return out;
}

}  // namespace

GaussianProcess fit_gaussian_process(const Eigen::MatrixXd& x, const Eigen::VectorXd& y, const NoiseBounds& noise,
                                     bool linear_trend) {
  const int n = int(x.rows()), k = int(x.cols());
  if (n < 2) throw std::runtime_error("a Gaussian process needs at least two runs");
  GaussianProcess gp;
  gp.x = x;
  // The trend needs runs beyond its k + 1 coefficients to leave the process something to fit.
  gp.trend = linear_trend && n >= k + 3;
  gp.y_mean = y.mean();
  double var = (y.array() - gp.y_mean).square().sum() / n;
  gp.y_scale = var > 0 ? std::sqrt(var) : 1.0;
  const Eigen::VectorXd ys = (y.array() - gp.y_mean) / gp.y_scale;
  // The noise bounds as variances of the standardised response.
  const double v_low = std::pow(noise.low / gp.y_scale, 2), v_high = std::pow(noise.high / gp.y_scale, 2);
  const std::vector<Candidate> all = candidates(x, ys, basis_matrix(gp), v_low, v_high);
  const Candidate* best = nullptr;
  for (const auto& c : all)
    if (!best || c.v.log_likelihood > best->v.log_likelihood + 1e-9) best = &c;
  if (!best) throw std::runtime_error("Gaussian process: no hyperparameters fit the runs");
  gp.length_scale = best->length_scale;
  gp.signal_variance = best->v.signal;
  gp.noise_ratio = best->v.ratio;
  gp.log_likelihood = best->v.log_likelihood;
  if (!condition(gp, ys)) throw std::runtime_error("Gaussian process: no hyperparameters fit the runs");
  return gp;
}

GaussianProcess with_response(const GaussianProcess& shape, const Eigen::VectorXd& y) {
  GaussianProcess gp = shape;
  const double n = double(y.size());
  gp.y_mean = y.mean();
  double var = (y.array() - gp.y_mean).square().sum() / n;
  gp.y_scale = var > 0 ? std::sqrt(var) : 1.0;
  const Eigen::VectorXd ys = (y.array() - gp.y_mean) / gp.y_scale;
  const Eigen::MatrixXd kinv_h = gp.chol.solve(gp.h);
  gp.beta = gp.h_kinv_h_inverse * (kinv_h.transpose() * ys);
  const Eigen::VectorXd r = ys - gp.h * gp.beta;
  gp.alpha = gp.chol.solve(r);
  const double dof = std::max(1.0, n - double(gp.h.cols()));
  gp.signal_variance = std::max(r.dot(gp.alpha) / dof, 1e-300);
  return gp;
}

Eigen::VectorXd GaussianProcess::basis(const Eigen::VectorXd& at) const {
  Eigen::VectorXd b(trend ? at.size() + 1 : 1);
  b[0] = 1;
  if (trend) b.tail(at.size()) = at;
  return b;
}

double GaussianProcess::noise_sd() const { return y_scale * std::sqrt(signal_variance * noise_ratio); }

double GaussianProcess::mean(const Eigen::VectorXd& at) const {
  double m = basis(at).dot(beta);
  for (int i = 0; i < x.rows(); ++i) m += kernel(at, x.row(i).transpose(), length_scale) * alpha[i];
  return y_mean + y_scale * m;
}

double GaussianProcess::sd(const Eigen::VectorXd& at) const {
  Eigen::VectorXd c(x.rows());
  for (int i = 0; i < x.rows(); ++i) c[i] = kernel(at, x.row(i).transpose(), length_scale);
  const Eigen::VectorXd kinv_c = chol.solve(c);
  // The trend's own uncertainty: u = h - H' K^-1 c, added as u' (H' K^-1 H)^-1 u.
  const Eigen::VectorXd u = basis(at) - h.transpose() * kinv_c;
  const double v = 1.0 - c.dot(kinv_c) + u.dot(h_kinv_h_inverse * u);
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
