#include "calibrate/posterior.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <stdexcept>

#include "calibrate/adaptive_loop.h"

namespace repose::calibrate {

namespace {

// Cell centres along each free factor: n per axis with n^free about 15 000 - 70 000 nodes.
int nodes_per_axis(int free) {
  switch (free) {
    case 1: return 401;
    case 2: return 121;
    case 3: return 41;
    case 4: return 17;
    default: return 0;  // Halton points
  }
}

void make_nodes(Posterior& p) {
  const int f = int(p.free.size());
  const int n = nodes_per_axis(f);
  if (n > 0) {
    p.per_axis.assign(size_t(f), n);
    p.cell = 2.0 / n;
    long total = 1;
    for (int d = 0; d < f; ++d) total *= n;
    for (long i = 0; i < total; ++i) {
      Eigen::VectorXd x = p.held;
      long code = i;
      for (int d = 0; d < f; ++d) {
        x[p.free[size_t(d)]] = -1 + (double(code % n) + 0.5) * p.cell;
        code /= n;
      }
      p.nodes.push_back(x);
    }
  } else {
    const int count = 60000;
    p.cell = 2.0 * std::pow(double(count), -1.0 / f);
    for (const auto& h : halton_points(f, 1, count)) {
      Eigen::VectorXd x = p.held;
      for (int d = 0; d < f; ++d) x[p.free[size_t(d)]] = h[d];
      p.nodes.push_back(x);
    }
  }
}

// log N(measured; mean, se^2 + sd^2 + the mean's spread over one cell, (|grad| cell)^2 / 12).
double log_likelihood(const Posterior& p, const PosteriorInput& in, const Eigen::VectorXd& x) {
  const double m = in.mean(x);
  double cell_var = 0;
  const double h = 1e-3;
  for (int d : p.free) {
    Eigen::VectorXd a = x, b = x;
    a[d] += h;
    b[d] -= h;
    const double slope = (in.mean(a) - in.mean(b)) / (2 * h);
    cell_var += slope * slope * p.cell * p.cell / 12;
  }
  const double sd = in.sd ? in.sd(x) : 0.0;
  const double var = in.measured_se * in.measured_se + sd * sd + cell_var + 1e-300;
  const double z = in.measured - m;
  return -0.5 * z * z / var - 0.5 * std::log(var);
}

// The 5 %, 50 % and 95 % points of a factor's marginal, mass spread evenly across each bin.
CredibleInterval marginal_of(const Posterior& p, int factor) {
  const int bins = p.per_axis.empty() ? 200 : p.per_axis[0];
  const double width = 2.0 / bins;
  std::vector<double> mass(size_t(bins), 0.0);
  CredibleInterval c;
  for (size_t i = 0; i < p.nodes.size(); ++i) {
    const double v = p.nodes[i][factor];
    mass[size_t(std::clamp(int((v + 1) / width), 0, bins - 1))] += p.mass[i];
    c.mean += p.mass[i] * v;
  }
  for (size_t i = 0; i < p.nodes.size(); ++i) c.sd += p.mass[i] * std::pow(p.nodes[i][factor] - c.mean, 2);
  c.sd = std::sqrt(c.sd);
  auto quantile = [&](double q) {
    double cum = 0;
    for (int b = 0; b < bins; ++b) {
      if (cum + mass[size_t(b)] >= q && mass[size_t(b)] > 0)
        return -1 + width * (b + (q - cum) / mass[size_t(b)]);
      cum += mass[size_t(b)];
    }
    return 1.0;
  };
  c.low = quantile(0.05);
  c.median = quantile(0.5);
  c.high = quantile(0.95);
  return c;
}

// The joint region (the most probable nodes holding 90 % of the mass), its extent and volume.
void joint_region(Posterior& p) {
  std::vector<size_t> order(p.mass.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return p.mass[a] > p.mass[b]; });
  double cum = 0;
  size_t inside = 0;
  while (inside < order.size() && cum < p.region_mass) cum += p.mass[order[inside++]];
  p.region_threshold = p.mass[order[inside - 1]];
  p.region_fraction = double(inside) / double(order.size());
  p.region_low = p.held;
  p.region_high = p.held;
  for (int d : p.free) {
    p.region_low[d] = INFINITY;
    p.region_high[d] = -INFINITY;
  }
  for (size_t k = 0; k < inside; ++k)
    for (int d : p.free) {
      p.region_low[d] = std::min(p.region_low[d], std::max(-1.0, p.nodes[order[k]][d] - 0.5 * p.cell));
      p.region_high[d] = std::max(p.region_high[d], std::min(1.0, p.nodes[order[k]][d] + 0.5 * p.cell));
    }
}

// The principal directions of the posterior's covariance over the free factors.
void ridge_of(Posterior& p) {
  const int f = int(p.free.size());
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(f, f);
  for (size_t i = 0; i < p.nodes.size(); ++i)
    for (int a = 0; a < f; ++a)
      for (int b = 0; b < f; ++b)
        cov(a, b) += p.mass[i] * (p.nodes[i][p.free[size_t(a)]] - p.marginal[size_t(p.free[size_t(a)])].mean) *
                     (p.nodes[i][p.free[size_t(b)]] - p.marginal[size_t(p.free[size_t(b)])].mean);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(cov);
  p.ridge = Eigen::VectorXd::Zero(p.factors);
  const Eigen::VectorXd top = eigen.eigenvectors().col(f - 1);
  // Sign: the largest component positive, so the direction reads the same on every run.
  int big = 0;
  for (int a = 1; a < f; ++a)
    if (std::abs(top[a]) > std::abs(top[big])) big = a;
  for (int a = 0; a < f; ++a) p.ridge[p.free[size_t(a)]] = top[big] < 0 ? -top[a] : top[a];
  p.ridge_sd = std::sqrt(std::max(0.0, eigen.eigenvalues()[f - 1]));
  p.across_sd = std::sqrt(std::max(0.0, eigen.eigenvalues()[0]));
}

}  // namespace

Posterior compute_posterior(int factors, const std::vector<PosteriorInput>& inputs, const std::vector<std::pair<int, double>>& held) {
  if (inputs.empty()) throw std::invalid_argument("a posterior needs at least one response");
  Posterior p;
  p.factors = factors;
  p.held = Eigen::VectorXd::Zero(factors);
  std::vector<bool> is_held(size_t(factors), false);
  for (auto [j, v] : held) {
    p.held[j] = v;
    is_held[size_t(j)] = true;
  }
  for (int j = 0; j < factors; ++j)
    if (!is_held[size_t(j)]) p.free.push_back(j);
  if (p.free.empty()) throw std::invalid_argument("a posterior needs a free factor");
  make_nodes(p);
  std::vector<double> log_mass(p.nodes.size(), 0.0);
  for (size_t i = 0; i < p.nodes.size(); ++i)
    for (const auto& in : inputs) log_mass[i] += log_likelihood(p, in, p.nodes[i]);
  const double top = *std::max_element(log_mass.begin(), log_mass.end());
  double total = 0;
  p.mass.resize(p.nodes.size());
  for (size_t i = 0; i < p.nodes.size(); ++i) total += p.mass[i] = std::exp(log_mass[i] - top);
  for (double& m : p.mass) m /= total;
  for (int j = 0; j < factors; ++j) {
    if (is_held[size_t(j)]) {
      p.marginal.push_back({p.held[j], p.held[j], p.held[j], p.held[j], 0});
    } else {
      p.marginal.push_back(marginal_of(p, j));
    }
  }
  joint_region(p);
  ridge_of(p);
  p.computed = true;
  return p;
}

int Posterior::nearest(const Eigen::VectorXd& coded) const {
  if (!per_axis.empty()) {
    long index = 0, stride = 1;
    for (size_t d = 0; d < free.size(); ++d) {
      const int n = per_axis[d];
      const int i = std::clamp(int(std::floor((coded[free[d]] + 1) / cell)), 0, n - 1);
      index += i * stride;
      stride *= n;
    }
    return int(index);
  }
  int best = 0;
  double best_d = INFINITY;
  for (size_t i = 0; i < nodes.size(); ++i) {
    double d = 0;
    for (int f : free) d += std::pow(nodes[i][f] - coded[f], 2);
    if (d < best_d) best_d = d, best = int(i);
  }
  return best;
}

bool Posterior::in_region(const Eigen::VectorXd& coded) const {
  return computed && mass[size_t(nearest(coded))] >= region_threshold;
}

std::string direction_text(const Eigen::VectorXd& direction, const std::vector<std::string>& names) {
  std::vector<int> order(size_t(direction.size()));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return std::abs(direction[a]) > std::abs(direction[b]); });
  std::string s;
  for (int j : order) {
    if (std::abs(direction[j]) < 0.005) continue;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s%.2f %s", s.empty() ? (direction[j] < 0 ? "-" : "+") : (direction[j] < 0 ? " - " : " + "),
                  std::abs(direction[j]), names[size_t(j)].c_str());
    s += buf;
  }
  return s;
}

}  // namespace repose::calibrate
