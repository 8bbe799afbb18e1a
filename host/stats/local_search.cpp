#include "stats/local_search.h"

#include <algorithm>
#include <cmath>

namespace repose::stats {

UnitMinimum nelder_mead(const UnitObjective& objective, const std::vector<double>& u, const std::vector<size_t>& free,
                        double size0, int budget, double value_tolerance) {
  size_t m = free.size();
  int evaluations = 0;
  auto f = [&](const std::vector<double>& p) {
    ++evaluations;
    return objective(p);
  };
  std::vector<std::vector<double>> x(m + 1, u);
  for (size_t k = 0; k < m; ++k) {
    size_t d = free[k];
    x[k + 1][d] = u[d] + (u[d] + size0 <= 1.0 ? size0 : -size0);
  }
  std::vector<double> fx(m + 1);
  for (size_t k = 0; k <= m; ++k) fx[k] = f(x[k]);
  auto along = [&](const std::vector<double>& centroid, const std::vector<double>& worst, double a) {
    std::vector<double> p = worst;
    for (size_t d : free) p[d] = std::clamp(centroid[d] + a * (worst[d] - centroid[d]), 0.0, 1.0);
    return p;
  };
  while (evaluations < budget) {
    std::vector<size_t> order(m + 1);
    for (size_t k = 0; k <= m; ++k) order[k] = k;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return fx[a] < fx[b]; });
    std::vector<std::vector<double>> xs;
    std::vector<double> fs;
    for (size_t k : order) {
      xs.push_back(x[k]);
      fs.push_back(fx[k]);
    }
    x = xs;
    fx = fs;
    double size = 0;
    for (size_t k = 1; k <= m; ++k)
      for (size_t d : free) size = std::max(size, std::abs(x[k][d] - x[0][d]));
    if (size < 1e-3 || (fx[m] - fx[0] < value_tolerance && size < 0.03)) break;
    std::vector<double> centroid = x[0];
    for (size_t d : free) {
      centroid[d] = 0;
      for (size_t k = 0; k < m; ++k) centroid[d] += x[k][d] / m;
    }
    auto xr = along(centroid, x[m], -1.0);
    double fr = f(xr);
    if (fr < fx[0]) {
      auto xe = along(centroid, x[m], -2.0);
      double fe = f(xe);
      if (fe < fr) {
        x[m] = xe;
        fx[m] = fe;
      } else {
        x[m] = xr;
        fx[m] = fr;
      }
    } else if (fr < fx[m - 1]) {
      x[m] = xr;
      fx[m] = fr;
    } else {
      auto xc = fr < fx[m] ? along(centroid, x[m], -0.5) : along(centroid, x[m], 0.5);
      double fc = f(xc);
      if (fc < std::min(fr, fx[m])) {
        x[m] = xc;
        fx[m] = fc;
      } else {
        for (size_t k = 1; k <= m; ++k) {
          for (size_t d : free) x[k][d] = x[0][d] + 0.5 * (x[k][d] - x[0][d]);
          fx[k] = f(x[k]);
        }
      }
    }
  }
  size_t best = size_t(std::min_element(fx.begin(), fx.end()) - fx.begin());
  return {x[best], fx[best]};
}

UnitMinimum golden_section(const UnitObjective& f, const std::vector<double>& u, size_t d, int evaluations) {
  const double r = 0.6180339887498949;
  double a = 0, b = 1;
  std::vector<double> p = u, q = u;
  p[d] = b - r * (b - a);
  q[d] = a + r * (b - a);
  double fp = f(p), fq = f(q);
  for (int i = 2; i < evaluations; ++i) {
    if (fp < fq) {
      b = q[d];
      q = p;
      fq = fp;
      p[d] = b - r * (b - a);
      fp = f(p);
    } else {
      a = p[d];
      p = q;
      fp = fq;
      q[d] = a + r * (b - a);
      fq = f(q);
    }
  }
  return fp < fq ? UnitMinimum{p, fp} : UnitMinimum{q, fq};
}

Eigen::VectorXd compass_maximise(const std::function<double(const Eigen::VectorXd&)>& score,
                                 const std::vector<Eigen::VectorXd>& candidates, double& top) {
  Eigen::VectorXd arg;
  top = -INFINITY;
  for (const auto& p : candidates) {
    double v = score(p);
    if (v > top) {
      top = v;
      arg = p;
    }
  }
  const Eigen::Index k = arg.size();
  for (double step = 0.05; step > 1e-4; step *= 0.5) {
    bool moved = true;
    while (moved) {
      moved = false;
      for (Eigen::Index d = 0; d < k; ++d)
        for (double dir : {-1.0, 1.0}) {
          Eigen::VectorXd p = arg;
          p[d] = std::clamp(p[d] + dir * step, -1.0, 1.0);
          double v = score(p);
          if (v > top + 1e-15) {
            top = v;
            arg = p;
            moved = true;
          }
        }
    }
  }
  return arg;
}

}  // namespace repose::stats
