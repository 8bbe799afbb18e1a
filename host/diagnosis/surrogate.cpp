#include "diagnosis/surrogate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "stats/local_search.h"
#include "stats/regression.h"

namespace repose {

namespace {

constexpr double kSamePoint = 1e-6;      // unit-cube distance below which two points are one
constexpr double kChaoticNear = 0.05;     // a chaotic fit's minimum this near a point: converged
constexpr double kConverged = 0.002;      // a smooth fit's minimum moving less than this: converged

double distance(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0;
  for (size_t k = 0; k < a.size(); ++k) d = std::max(d, std::abs(a[k] - b[k]));
  return d;
}

// The same process for another response over the same design: the hyperparameters, the kernel
// matrix and its factor are shared, the response standardised and solved again (as
// fit_gaussian_process does for its own).
calibrate::GaussianProcess with_response(const calibrate::GaussianProcess& shape, const Eigen::VectorXd& y) {
  calibrate::GaussianProcess gp = shape;
  const double n = double(y.size());
  gp.y_mean = y.mean();
  double var = (y.array() - gp.y_mean).square().sum() / n;
  gp.y_scale = var > 0 ? std::sqrt(var) : 1.0;
  Eigen::VectorXd ys = (y.array() - gp.y_mean) / gp.y_scale;
  gp.alpha = gp.chol.solve(ys);
  gp.signal_variance = std::max(ys.dot(gp.alpha) / n, 1e-300);
  return gp;
}

}  // namespace

// Processes for one response per group (`of(point, group)`), each on the residual of a quadratic
// trend over the design (least squares): a drop's rebound spans a hundred times the data's noise
// across the cube, and a stationary process fitted to that whole range smooths over what the data
// resolve. A residual that varies no more than twice a point's own noise (`noise`, a chaotic
// model's variance of a point's mean) is that noise: the surface is then the trend alone, which a
// process would only bend through the points' luck. The hyperparameters are fitted once per
// measure (its conditions and a series' times respond alike): on the group whose residual varies
// most.
std::vector<GroupSurface> fit_group_surfaces(const Observations& obs, const Eigen::MatrixXd& x,
                                             const std::function<double(size_t, size_t)>& of,
                                             const std::vector<double>& noise) {
  const size_t points = size_t(x.rows()), groups = obs.groups.size();
  std::vector<stats::Term> trend = stats::build_model(stats::ModelKind::quadratic, int(x.cols()));
  if (points < trend.size() + 2) trend = stats::build_model(stats::ModelKind::mean, int(x.cols()));
  Eigen::MatrixXd design = stats::model_matrix(trend, x);
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(design);
  const double dof = double(points - trend.size());
  std::vector<GroupSurface> out(groups);
  std::vector<Eigen::VectorXd> residual(groups);
  std::map<std::string, size_t> representative;
  for (size_t g = 0; g < groups; ++g) {
    Eigen::VectorXd y = Eigen::VectorXd::Zero(long(points));
    for (size_t p = 0; p < points; ++p) y[long(p)] = of(p, g);
    out[g].trend = trend;
    out[g].coef = qr.solve(y);
    residual[g] = y - design * out[g].coef;
    if (!noise.empty()) {
      out[g].has_process = residual[g].squaredNorm() / dof > 2 * noise[g];
      out[g].trend_variance = noise[g] * double(trend.size()) / double(points);
    }
    if (!out[g].has_process) continue;
    const std::string& key = obs.groups[g].measure;
    auto it = representative.find(key);
    if (it == representative.end() || residual[g].squaredNorm() > residual[it->second].squaredNorm())
      representative[key] = g;
  }
  std::map<std::string, calibrate::GaussianProcess> fitted;
  for (const auto& [key, g] : representative) fitted[key] = calibrate::fit_gaussian_process(x, residual[g]);
  for (size_t g = 0; g < groups; ++g) {
    if (!out[g].has_process) continue;
    const std::string& key = obs.groups[g].measure;
    out[g].process = representative[key] == g ? fitted[key] : with_response(fitted[key], residual[g]);
  }
  return out;
}

double GroupSurface::mean(const Eigen::VectorXd& at) const {
  double m = has_process ? process.mean(at) : 0.0;
  for (size_t t = 0; t < trend.size(); ++t) m += coef[long(t)] * stats::term_value(trend[t], at.data());
  return m;
}

double GroupSurface::latent_variance(const Eigen::VectorXd& at) const {
  if (!has_process) return trend_variance;
  double sd = process.sd(at);
  return sd * sd;
}

ModelSurrogate::ModelSurrogate(Predictor& predictor, const ModelExtension* extension,
                               std::function<void(const std::string&)> on_point)
    : predictor_(predictor), extension_(extension), parameters_(predictor.parameters(extension)),
      on_point_(std::move(on_point)) {
  stochastic_ = predictor.stochastic(extension, values(std::vector<double>(parameters_.size(), 0.5)));
  // A heap (the expensive, chaotic role): each point its own fills, half the replicates.
  chaotic_ = stochastic_ && predictor.expensive();
  const Observations& obs = predictor.observations();
  scatter_scored_ = std::any_of(obs.groups.begin(), obs.groups.end(),
                                [](const ObservationGroup& g) { return g.sigma_given && g.values.size() >= 2; });
  int r = predictor.simulated_replicates();
  replicates_ = !stochastic_ ? 1 : chaotic_ ? std::max(2, (r + 1) / 2) : r;
}

std::vector<double> ModelSurrogate::values(const std::vector<double>& u) const {
  std::vector<double> v(parameters_.size());
  for (size_t k = 0; k < v.size(); ++k) v[k] = parameters_[k].from_unit(u[k]);
  return v;
}

namespace {

// Design sizes: a grid of `grid` steps per axis over the whole cube and, for an extension, a line of
// `line` steps along its own parameters through the baseline's values (where its effect must be
// resolved against the baseline's, however steep the baseline's own response is).
int grid_steps(size_t k) { return k == 1 ? 6 : 2; }
int line_steps(bool noisy) { return noisy ? 4 : 6; }

}  // namespace

int ModelSurrogate::planned_points(size_t k, size_t conditions, bool noisy) {
  if (k == 0) return 1;
  int grid = 1;
  for (size_t d = 0; d < k; ++d) grid *= grid_steps(k) + 1;
  int line = k > 1 ? line_steps(noisy) + 1 : 0;
  int valley = k > 1 ? (noisy ? 1 : 2) * line : 0;  // passes that usually suffice
  return grid + line + valley + (noisy ? 3 : 4) + (conditions >= 3 ? int(conditions) : 0);  // refinement, held out
}

void ModelSurrogate::simulate_design(const std::vector<double>& near) {
  const size_t k = parameters_.size();
  if (k == 0) {
    simulate({});
    return;
  }
  const int steps = grid_steps(k);
  int total = 1;
  for (size_t d = 0; d < k; ++d) total *= steps + 1;
  for (int i = 0; i < total; ++i) {
    std::vector<double> u(k);
    for (size_t d = 0, code = size_t(i); d < k; ++d, code /= size_t(steps + 1))
      u[d] = double(code % size_t(steps + 1)) / steps;
    simulate(u);
  }
  if (near.empty()) return;
  // The line: the baseline's values held, each of the extension's own parameters over its range.
  size_t held = predictor_.parameters(nullptr).size();
  for (size_t d = held; d < k; ++d)
    for (int j = 0; j <= line_steps(chaotic_); ++j) {
      std::vector<double> u = near;
      u[d] = double(j) / line_steps(chaotic_);
      line_.push_back(u);
      simulate(u);
    }
}

void ModelSurrogate::trace_valley(const std::vector<char>& use, int passes) {
  const Observations& obs = predictor_.observations();
  size_t held = predictor_.parameters(nullptr).size();
  if (line_.empty() || held == 0) return;
  std::vector<size_t> dims(held);
  for (size_t d = 0; d < held; ++d) dims[d] = d;
  for (int pass = 0; pass < passes; ++pass) {
    refit();
    // Along the line the baseline's parameters refitted on the surface, the extension's held.
    std::vector<std::pair<std::vector<double>, double>> valley;
    for (const std::vector<double>& point : line_) {
      stats::UnitObjective objective = [&](const std::vector<double>& u) {
        return chi_square(obs, predict(u), use);
      };
      stats::UnitMinimum m = stats::nelder_mead(objective, point, dims, 0.05, 100, 1e-5);
      valley.push_back({m.x, m.value});
    }
    bool agreed = true;
    for (const auto& [u, surface] : valley) {
      double nearest = std::numeric_limits<double>::infinity();
      for (const auto& p : design_) nearest = std::min(nearest, distance(p, u));
      if (nearest < kConverged) continue;
      double exact = chi_square(obs, simulate(u), use);
      agreed = agreed && std::abs(exact - surface) <= std::max(0.5, 0.02 * exact);
    }
    if (agreed || chaotic_) break;
  }
}

Prediction ModelSurrogate::simulate(const std::vector<double>& u) {
  for (size_t p = 0; p < design_.size(); ++p)
    if (distance(design_[p], u) < kSamePoint) return simulated_[p];
  std::vector<char> all(predictor_.observations().conditions.size(), 1);
  // A chaotic model's point takes fills no other point (nor the confirmation) uses.
  int first = chaotic_ ? predictor_.confirmation_first() + predictor_.confirmation_replicates() +
                             int(design_.size()) * replicates_
                       : 0;
  Prediction p = predictor_.predict(extension_, values(u), all, first, replicates_);
  design_.push_back(u);
  simulated_.push_back(std::move(p));
  stale_ = true;
  if (on_point_) on_point_(extension_ ? extension_->id : "baseline");
  return simulated_.back();
}

void ModelSurrogate::refit() {
  if (!stale_) return;
  stale_ = false;
  if (design_.size() < 2) return;
  const Observations& obs = predictor_.observations();
  Eigen::MatrixXd x(long(design_.size()), long(parameters_.size()));
  for (size_t p = 0; p < design_.size(); ++p)
    for (size_t d = 0; d < parameters_.size(); ++d) x(long(p), long(d)) = design_[p][d];
  pooled_var_.assign(obs.groups.size(), 0.0);
  for (const Prediction& p : simulated_)
    for (size_t g = 0; g < p.var.size(); ++g) pooled_var_[g] += p.var[g] / double(simulated_.size());
  // A chaotic model's point mean carries its replicates' scatter: the noise a surface must not follow.
  std::vector<double> noise;
  if (chaotic_)
    for (double v : pooled_var_) noise.push_back(v / replicates_);
  mean_ = fit_group_surfaces(obs, x, [&](size_t p, size_t g) { return simulated_[p].mean[g]; }, noise);
  // The replicate scatter as a surface where the data score it (sigma given), else pooled over the
  // points (it then weighs only the means' own uncertainty).
  if (stochastic_ && scatter_scored_)
    sd_ = fit_group_surfaces(obs, x, [&](size_t p, size_t g) { return std::sqrt(simulated_[p].var[g]); }, {});
}

Prediction ModelSurrogate::predict(const std::vector<double>& u) const {
  if (design_.size() == 1 || parameters_.empty()) return simulated_.front();
  if (stale_) throw std::logic_error("ModelSurrogate::predict before refit");
  const size_t groups = mean_.size();
  Eigen::VectorXd at(long(u.size()));
  for (size_t d = 0; d < u.size(); ++d) at[long(d)] = u[d];
  Prediction out;
  out.replicates = replicates_;
  out.mean.resize(groups);
  out.var.assign(groups, 0.0);
  for (size_t g = 0; g < groups; ++g) out.mean[g] = mean_[g].mean(at);
  if (!stochastic_) return out;
  // A mean is known no better than from its replicates (a clump's common orientations), or, for
  // a chaotic model, than from every point's replicates pooled.
  int pooled = replicates_ * (chaotic_ ? int(design_.size()) : 1);
  out.mean_var.resize(groups);
  for (size_t g = 0; g < groups; ++g) {
    double sd = scatter_scored_ ? std::max(0.0, sd_[g].mean(at)) : 0.0;
    out.var[g] = scatter_scored_ ? sd * sd : pooled_var_[g];
    out.mean_var[g] = std::max(mean_[g].latent_variance(at), out.var[g] / pooled);
  }
  return out;
}

Prediction ModelSurrogate::surface(const std::vector<double>& u) {
  refit();
  return predict(u);
}

SurfaceMinimum ModelSurrogate::minimise(const std::vector<char>& use, const Prediction* target) {
  const Observations& obs = predictor_.observations();
  SurfaceMinimum best;
  if (parameters_.empty()) {
    best.prediction = simulated_.front();
    best.score = chi_square(obs, best.prediction, use, target);
    best.simulated = true;
    return best;
  }
  refit();
  stats::UnitObjective objective = [&](const std::vector<double>& u) {
    return chi_square(obs, predict(u), use, target);
  };
  // Starts: the three design points the surface scores best.
  std::vector<std::pair<double, size_t>> ranked;
  for (size_t p = 0; p < design_.size(); ++p) ranked.push_back({objective(design_[p]), p});
  std::sort(ranked.begin(), ranked.end());
  std::vector<size_t> dims(parameters_.size());
  for (size_t d = 0; d < dims.size(); ++d) dims[d] = d;
  best.score = std::numeric_limits<double>::infinity();
  for (size_t s = 0; s < std::min<size_t>(3, ranked.size()); ++s) {
    stats::UnitMinimum m = stats::nelder_mead(objective, design_[ranked[s].second], dims, 0.05, 200, 1e-5);
    if (m.value < best.score) {
      best.score = m.value;
      best.u = m.x;
    }
  }
  best.prediction = predict(best.u);
  return best;
}

SurfaceMinimum ModelSurrogate::fit(const std::vector<char>& use, const Prediction* target, int new_points) {
  const Observations& obs = predictor_.observations();
  SurfaceMinimum m = minimise(use, target);
  for (int added = 0; added < new_points && !m.simulated; ++added) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& p : design_) nearest = std::min(nearest, distance(p, m.u));
    if (chaotic_ && nearest < kChaoticNear) break;
    Prediction at = simulate(m.u);
    double exact = chi_square(obs, at, use, target);
    SurfaceMinimum next = minimise(use, target);
    // Converged: the simulation agrees with the surface, and the surface refitted with it keeps
    // its minimum there.
    if (!chaotic_ && std::abs(exact - m.score) <= std::max(0.05, 0.005 * exact) &&
        distance(next.u, m.u) < kConverged) {
      m.score = exact;
      m.prediction = at;
      m.simulated = true;
      break;
    }
    m = next;
  }
  if (chaotic_ || parameters_.empty()) return m;
  // A smooth model's simulated points are exact: none may beat what the fit returns.
  for (size_t p = 0; p < design_.size(); ++p) {
    double exact = chi_square(obs, simulated_[p], use, target);
    if (exact < m.score - 1e-9 || (!m.simulated && exact <= m.score)) {
      m.u = design_[p];
      m.score = exact;
      m.prediction = simulated_[p];
      m.simulated = true;
    }
  }
  return m;
}

}  // namespace repose
