#include "diagnosis/model_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace repose {

std::vector<double> group_chi_squares(const Observations& obs, const Prediction& predicted, const Prediction* target) {
  size_t groups = obs.groups.size();
  std::vector<double> z(groups), out(groups);
  for (size_t g = 0; g < groups; ++g) {
    const ObservationGroup& grp = obs.groups[g];
    double n = double(grp.values.size());
    double v = predicted.var.empty() ? 0.0 : predicted.var[g];
    double V = grp.sigma_given ? grp.sd * grp.sd + v : grp.sd * grp.sd;
    double var_mean = V / n + (predicted.replicates > 1 ? v / predicted.replicates : 0.0);
    double mean = target ? target->mean[g] : grp.mean;
    z[g] = (mean - predicted.mean[g]) / std::sqrt(var_mean);
    if (grp.sigma_given && grp.values.size() >= 2) {
      double s2 = target ? grp.sd * grp.sd + (target->var.empty() ? 0.0 : target->var[g]) : grp.s2;
      double q = std::max(s2, 1e-300) / V;
      out[g] = (n - 1) * (q - 1 - std::log(q));
    }
  }
  for (size_t g = 0; g < groups; ++g) {
    const ObservationGroup& grp = obs.groups[g];
    double rho = grp.series ? obs.noise.at(grp.measure).rho : 0.0;
    double w = z[g];
    if (grp.previous >= 0 && rho > 0) w = (z[g] - rho * z[size_t(grp.previous)]) / std::sqrt(1 - rho * rho);
    out[g] += w * w;
  }
  return out;
}

double chi_square(const Observations& obs, const Prediction& predicted, const std::vector<char>& use,
                  const Prediction* target) {
  std::vector<double> terms = group_chi_squares(obs, predicted, target);
  double chi2 = 0;
  for (size_t g = 0; g < obs.groups.size(); ++g)
    if (use[obs.groups[g].condition]) chi2 += terms[g];
  return chi2;
}

int score_terms(const Observations& obs) {
  int terms = 0;
  for (const auto& g : obs.groups) terms += 1 + (g.sigma_given && g.values.size() >= 2 ? 1 : 0);
  return terms;
}

ModelFit fit_model(Predictor& predictor, const ModelExtension* extension, const std::vector<char>& use,
                   const std::vector<double>& start, double step, int max_evaluations,
                   const Prediction* target) {
  const Observations& obs = predictor.observations();
  auto params = predictor.parameters(extension);
  size_t n = params.size();
  ModelFit fit;
  for (const auto& g : obs.groups) fit.groups += use[g.condition] ? 1 : 0;
  auto values = [&](const std::vector<double>& u) {
    std::vector<double> v(n);
    for (size_t k = 0; k < n; ++k) v[k] = params[k].from_unit(u[k]);
    return v;
  };
  auto objective = [&](const std::vector<double>& u) {
    ++fit.evaluations;
    return chi_square(obs, predictor.predict(extension, values(u), use), use, target);
  };

  std::vector<double> u0(n, 0.5);
  for (size_t k = 0; k < n; ++k) {
    if (k < start.size()) u0[k] = std::clamp(params[k].to_unit(start[k]), 0.0, 1.0);
    else if (predictor.fits_baseline() && k == 0) u0[k] = params[0].to_unit(predictor.case_baseline_value());
  }
  if (n == 0) {
    fit.predicted = predictor.predict(extension, {}, use);
    fit.chi2 = chi_square(obs, fit.predicted, use, target);
    return fit;
  }
  // Nelder-Mead (standard coefficients) over the dimensions in `free`, the others held; the
  // simplex kept inside the unit cube by clamping. Returns the best point and its value.
  auto nelder_mead = [&](std::vector<double> u, const std::vector<size_t>& free, double size0, int budget) {
    size_t m = free.size();
    int stop = fit.evaluations + budget;
    std::vector<std::vector<double>> x(m + 1, u);
    for (size_t k = 0; k < m; ++k) {
      size_t d = free[k];
      x[k + 1][d] = u[d] + (u[d] + size0 <= 1.0 ? size0 : -size0);
    }
    std::vector<double> f(m + 1);
    for (size_t k = 0; k <= m; ++k) f[k] = objective(x[k]);
    auto along = [&](const std::vector<double>& centroid, const std::vector<double>& worst, double a) {
      std::vector<double> p = worst;
      for (size_t d : free) p[d] = std::clamp(centroid[d] + a * (worst[d] - centroid[d]), 0.0, 1.0);
      return p;
    };
    while (fit.evaluations < stop) {
      std::vector<size_t> order(m + 1);
      for (size_t k = 0; k <= m; ++k) order[k] = k;
      std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return f[a] < f[b]; });
      std::vector<std::vector<double>> xs;
      std::vector<double> fs;
      for (size_t k : order) { xs.push_back(x[k]); fs.push_back(f[k]); }
      x = xs;
      f = fs;
      double size = 0;
      for (size_t k = 1; k <= m; ++k)
        for (size_t d : free) size = std::max(size, std::abs(x[k][d] - x[0][d]));
      // 0.01 in chi^2 is far below any decision; a small simplex is converged.
      if (size < 1e-3 || (f[m] - f[0] < 0.01 && size < 0.03)) break;
      std::vector<double> centroid = x[0];
      for (size_t d : free) {
        centroid[d] = 0;
        for (size_t k = 0; k < m; ++k) centroid[d] += x[k][d] / m;
      }
      auto xr = along(centroid, x[m], -1.0);
      double fr = objective(xr);
      if (fr < f[0]) {
        auto xe = along(centroid, x[m], -2.0);
        double fe = objective(xe);
        if (fe < fr) { x[m] = xe; f[m] = fe; } else { x[m] = xr; f[m] = fr; }
      } else if (fr < f[m - 1]) {
        x[m] = xr;
        f[m] = fr;
      } else {
        auto xc = fr < f[m] ? along(centroid, x[m], -0.5) : along(centroid, x[m], 0.5);
        double fc = objective(xc);
        if (fc < std::min(fr, f[m])) {
          x[m] = xc;
          f[m] = fc;
        } else {
          for (size_t k = 1; k <= m; ++k) {
            for (size_t d : free) x[k][d] = x[0][d] + 0.5 * (x[k][d] - x[0][d]);
            f[k] = objective(x[k]);
          }
        }
      }
    }
    size_t best = std::min_element(f.begin(), f.end()) - f.begin();
    return std::make_pair(x[best], f[best]);
  };

  // Golden-section search of one dimension over its whole range (the profile's inner fit).
  auto golden = [&](std::vector<double> u, size_t d, int evaluations) {
    const double r = 0.6180339887498949;
    double a = 0, b = 1;
    std::vector<double> p = u, q = u;
    p[d] = b - r * (b - a);
    q[d] = a + r * (b - a);
    double fp = objective(p), fq = objective(q);
    for (int i = 2; i < evaluations; ++i) {
      if (fp < fq) {
        b = q[d];
        q = p;
        fq = fp;
        p[d] = b - r * (b - a);
        fp = objective(p);
      } else {
        a = p[d];
        p = q;
        fp = fq;
        q[d] = a + r * (b - a);
        fq = objective(q);
      }
    }
    return fp < fq ? std::make_pair(p, fp) : std::make_pair(q, fq);
  };

  std::vector<size_t> all_dims(n);
  for (size_t k = 0; k < n; ++k) all_dims[k] = k;
  // Parameters without a start value: scan the first of them over its range, the started ones
  // refitted at each point (a profile: they trade off against each other), and start where it
  // fits best. The range's low end is the extension nearly off, so the fit starts no worse than
  // the model without it.
  if (start.size() < n) {
    size_t k = start.size();
    std::vector<size_t> held(start.size());
    for (size_t j = 0; j < held.size(); ++j) held[j] = j;
    double best = std::numeric_limits<double>::infinity();
    std::vector<double> best_u = u0;
    // A heap costs ~1000 drops: a coarser profile (6 points, 8 evaluations each) there.
    int points = predictor.expensive() ? 5 : 9, inner = predictor.expensive() ? 8 : 14;
    for (int i = 0; i <= points; ++i) {
      std::vector<double> u = u0;
      u[k] = double(i) / points;
      auto [ui, fi] = held.empty()       ? std::make_pair(u, objective(u))
                      : held.size() == 1 ? golden(u, held[0], inner)
                                         : nelder_mead(u, held, 0.04, 12);
      if (fi < best) { best = fi; best_u = ui; }
    }
    u0 = best_u;
    step = std::min(step, 0.08);
  }
  if (predictor.expensive()) max_evaluations = std::min(max_evaluations, 24);
  auto [u_best, f_best] = nelder_mead(u0, all_dims, step, max_evaluations);
  fit.params = values(u_best);
  fit.predicted = predictor.predict(extension, fit.params, use);  // cached
  fit.chi2 = f_best;
  return fit;
}

}  // namespace repose
