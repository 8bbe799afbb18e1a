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
constexpr double kNearRadius = 0.1;       // a fit started near a known minimum searches this far first

double distance(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0;
  for (size_t k = 0; k < a.size(); ++k) d = std::max(d, std::abs(a[k] - b[k]));
  return d;
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
  for (const auto& [key, g] : representative) fitted[key] = calibrate::fit_gaussian_process(x, residual[g], {}, false);  // the residual has no trend left
  for (size_t g = 0; g < groups; ++g) {
    if (!out[g].has_process) continue;
    const std::string& key = obs.groups[g].measure;
    out[g].process = representative[key] == g ? fitted[key] : calibrate::with_response(fitted[key], residual[g]);
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

// Design sizes: a grid of `kGridSteps` steps per axis over the whole cube (one parameter: 6) and,
// for an extension, a line of `kLineSteps` steps along its own parameters through the baseline's
// values (where its effect must be resolved against the baseline's, however steep the baseline's
// own response is).
int grid_steps(size_t k) { return k == 1 ? 6 : 2; }
constexpr int kLineSteps = 4;

}  // namespace

int ModelSurrogate::planned_points(size_t k, size_t conditions, bool chaotic) {
  if (k == 0) return 1;
  int grid = 1;
  for (size_t d = 0; d < k; ++d) grid *= grid_steps(k) + 1;
  int line = k > 1 ? kLineSteps + 1 : 0;
  int valley = k > 1 ? (chaotic ? 1 : 2) * line : 0;  // the passes that usually suffice
  int refine = chaotic ? 3 : 5, held_out = conditions >= 3 ? int(conditions) : 0;
  return grid + line + valley + refine + held_out;
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
    for (int j = 0; j <= kLineSteps; ++j) {
      std::vector<double> u = near;
      u[d] = double(j) / kLineSteps;
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
  std::vector<std::vector<double>> starts = line_;  // each pass from the last pass's valley
  for (int pass = 0; pass < passes; ++pass) {
    refit();
    // Along the line the baseline's parameters refitted on the surface, the extension's held.
    std::vector<std::pair<std::vector<double>, double>> valley;
    stats::UnitObjective objective = [&](const std::vector<double>& u) { return chi_square(obs, predict(u), use); };
    for (std::vector<double>& start : starts) {
      stats::UnitMinimum m = stats::nelder_mead(objective, start, dims, 0.05, 100, 1e-5);
      valley.push_back({m.x, m.value});
      start = m.x;
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
  return minimise_within(use, target, {}, 1.0);
}

SurfaceMinimum ModelSurrogate::minimise_within(const std::vector<char>& use, const Prediction* target,
                                               const std::vector<double>& centre, double radius) {
  const Observations& obs = predictor_.observations();
  SurfaceMinimum best;
  if (parameters_.empty()) {
    best.prediction = simulated_.front();
    best.score = chi_square(obs, best.prediction, use, target);
    best.simulated = true;
    return best;
  }
  refit();
  const size_t k = parameters_.size();
  // The box searched, [centre - radius, centre + radius] within the cube (the whole cube without
  // a centre); the search runs in its own unit cube.
  std::vector<double> lo(k, 0.0), hi(k, 1.0);
  for (size_t d = 0; d < k && !centre.empty(); ++d) {
    lo[d] = std::max(0.0, centre[d] - radius);
    hi[d] = std::min(1.0, centre[d] + radius);
  }
  auto in_box = [&](const std::vector<double>& v) {
    std::vector<double> u(k);
    for (size_t d = 0; d < k; ++d) u[d] = lo[d] + std::clamp(v[d], 0.0, 1.0) * (hi[d] - lo[d]);
    return u;
  };
  auto to_box = [&](const std::vector<double>& u) {
    std::vector<double> v(k);
    for (size_t d = 0; d < k; ++d) v[d] = hi[d] > lo[d] ? std::clamp((u[d] - lo[d]) / (hi[d] - lo[d]), 0.0, 1.0) : 0.0;
    return v;
  };
  stats::UnitObjective objective = [&](const std::vector<double>& v) {
    return chi_square(obs, predict(in_box(v)), use, target);
  };
  // Starts: the centre, else the three design points the surface scores best and, for a smooth
  // model, the one the simulations score best (the surface may be wrong there).
  std::vector<std::vector<double>> starts;
  if (!centre.empty()) {
    starts.push_back(centre);
  } else {
    std::vector<std::pair<double, size_t>> ranked;
    for (size_t p = 0; p < design_.size(); ++p) ranked.push_back({objective(to_box(design_[p])), p});
    std::sort(ranked.begin(), ranked.end());
    for (size_t s = 0; s < std::min<size_t>(3, ranked.size()); ++s) starts.push_back(design_[ranked[s].second]);
    if (!chaotic_) starts.push_back(design_[best_simulated(use, target)]);
  }
  std::vector<size_t> dims(k);
  for (size_t d = 0; d < k; ++d) dims[d] = d;
  best.score = std::numeric_limits<double>::infinity();
  for (const auto& start : starts) {
    stats::UnitMinimum m = stats::nelder_mead(objective, to_box(start), dims, 0.05, 200, 1e-5);
    if (m.value < best.score) {
      best.score = m.value;
      best.u = in_box(m.x);
    }
  }
  best.prediction = predict(best.u);
  return best;
}

size_t ModelSurrogate::best_simulated(const std::vector<char>& use, const Prediction* target) const {
  const Observations& obs = predictor_.observations();
  size_t best = 0;
  double score = std::numeric_limits<double>::infinity();
  for (size_t p = 0; p < design_.size(); ++p) {
    double exact = chi_square(obs, simulated_[p], use, target);
    if (exact < score) {
      score = exact;
      best = p;
    }
  }
  return best;
}

SurfaceMinimum ModelSurrogate::fit(const std::vector<char>& use, const Prediction* target, int new_points,
                                   const std::vector<double>& near) {
  if (chaotic_ || parameters_.empty()) return fit_chaotic(use, target, new_points);
  const Observations& obs = predictor_.observations();
  // A trust region around the best simulated point: the surface's minimum in the region is
  // simulated; a better point moves the region there (and widens it where the surface agreed),
  // a worse one halves it. The first step searches the whole cube, or near `near`.
  double radius = near.empty() ? 0.25 : kNearRadius;
  SurfaceMinimum m = near.empty() ? minimise(use, target) : minimise_within(use, target, near, radius);
  for (int added = 0; added < new_points && radius > kConverged; ++added) {
    size_t incumbent = best_simulated(use, target);
    double before = chi_square(obs, simulated_[incumbent], use, target);
    Prediction at = simulate(m.u);
    double exact = chi_square(obs, at, use, target);
    bool agreed = std::abs(exact - m.score) <= std::max(0.05, 0.005 * exact);
    bool moved = distance(m.u, design_[incumbent]) >= kConverged;
    if (agreed && !moved) break;  // the surface's minimum is the best point, and it is exact there
    if (exact < before) radius = agreed ? std::min(0.5, 2 * radius) : radius;
    else radius /= 2;
    m = minimise_within(use, target, design_[best_simulated(use, target)], radius);
  }
  // The result is the best simulated point: a smooth model's points are exact.
  size_t best = best_simulated(use, target);
  m.u = design_[best];
  m.prediction = simulated_[best];
  m.score = chi_square(obs, m.prediction, use, target);
  m.simulated = true;
  return m;
}

SurfaceMinimum ModelSurrogate::fit_chaotic(const std::vector<char>& use, const Prediction* target, int new_points) {
  SurfaceMinimum m = minimise(use, target);
  for (int added = 0; added < new_points && !m.simulated; ++added) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& p : design_) nearest = std::min(nearest, distance(p, m.u));
    if (nearest < kChaoticNear) break;
    simulate(m.u);
    m = minimise(use, target);
  }
  return m;
}

}  // namespace repose
