#include "stats/optimize.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "stats/halton.h"
#include "stats/errors.h"

namespace repose::stats {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

void check_box(const Box& box) {
  if (box.lower.size() == 0 || box.lower.size() != box.upper.size())
    throw StatsError("optimisation bounds: lower and upper need one value per factor");
  for (Eigen::Index i = 0; i < box.lower.size(); ++i)
    if (!(box.lower[i] <= box.upper[i]) || !std::isfinite(box.lower[i]) || !std::isfinite(box.upper[i]))
      throw StatsError("optimisation bounds of factor " + std::to_string(i + 1) +
                       " are reversed or not finite");
}

std::vector<int> free_dims(const Box& box) {
  std::vector<int> out;
  for (Eigen::Index i = 0; i < box.lower.size(); ++i)
    if (box.upper[i] > box.lower[i]) out.push_back(static_cast<int>(i));
  return out;
}

Eigen::VectorXd clamp(const Eigen::VectorXd& x, const Box& box) {
  return x.cwiseMax(box.lower).cwiseMin(box.upper);
}

// Hooke-Jeeves pattern search on the box: exploratory coordinate moves of h * range, pattern
// moves along the last improvement, h halved when nothing improves. Derivative-free, so it
// handles desirability's kinks, and deterministic.
Eigen::VectorXd pattern_search(const Objective& f, const Box& box, const std::vector<int>& dims,
                               Eigen::VectorXd x, double& fx) {
  x = clamp(x, box);
  fx = f(x);
  const double h_min = 1e-10;
  long evaluations = 0;
  const long max_evaluations = 200000;
  auto explore = [&](Eigen::VectorXd b, double fb, double h, double& out) {
    for (int i : dims) {
      double range = box.upper[i] - box.lower[i];
      double keep = b[i];
      bool moved = false;
      for (double dir : {1.0, -1.0}) {
        b[i] = std::clamp(keep + dir * h * range, box.lower[i], box.upper[i]);
        if (b[i] == keep) continue;
        double fb_new = f(b);
        ++evaluations;
        if (fb_new < fb) {
          fb = fb_new;
          moved = true;
          break;
        }
      }
      if (!moved) b[i] = keep;
    }
    out = fb;
    return b;
  };
  double h = 0.25;
  while (h >= h_min && evaluations < max_evaluations) {
    double fy;
    Eigen::VectorXd y = explore(x, fx, h, fy);
    if (fy < fx) {
      for (;;) {
        Eigen::VectorXd p = clamp(2 * y - x, box);
        double fp = f(p), fz;
        ++evaluations;
        Eigen::VectorXd z = explore(p, fp, h, fz);
        x = y;
        fx = fy;
        if (fz < fy && evaluations < max_evaluations) {
          y = z;
          fy = fz;
        } else {
          break;
        }
      }
    } else {
      h *= 0.5;
    }
  }
  return x;
}

// Best of the pattern searches started from the centre, the corners (up to 6 free factors)
// and Halton points of the box.
Eigen::VectorXd multi_start(const Objective& f, const Box& box, const OptimizeOptions& opt,
                            double& best_f) {
  auto dims = free_dims(box);
  const int m = static_cast<int>(dims.size());
  std::vector<Eigen::VectorXd> starts;
  Eigen::VectorXd centre = 0.5 * (box.lower + box.upper);
  starts.push_back(centre);
  if (m <= 6)
    for (int c = 0; c < (1 << m); ++c) {
      Eigen::VectorXd s = centre;
      for (int j = 0; j < m; ++j) s[dims[j]] = ((c >> j) & 1) ? box.upper[dims[j]] : box.lower[dims[j]];
      starts.push_back(s);
    }
  static const int primes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53,
                               59, 61, 67, 71, 73, 79, 83, 89, 97};
  for (int s = 1; s <= opt.halton_starts && m > 0; ++s) {
    Eigen::VectorXd p = centre;
    for (int j = 0; j < m; ++j) {
      int i = dims[j];
      p[i] = box.lower[i] + radical_inverse(s, primes[j % 25]) * (box.upper[i] - box.lower[i]);
    }
    starts.push_back(p);
  }
  Eigen::VectorXd best;
  best_f = kInf;
  for (const auto& s : starts) {
    double fs;
    Eigen::VectorXd x = pattern_search(f, box, dims, s, fs);
    if (fs < best_f) {  // strict: ties keep the earlier start, so the result is reproducible
      best_f = fs;
      best = x;
    }
  }
  return best;
}

// Samples the box on a grid of the free factors; `member` decides who belongs to the set.
// Fills the set's extent, its main direction and spread-out representatives.
void describe_set(Optimum& opt, const Objective& value_of, const Box& box,
                  const OptimizeOptions& options,
                  const std::function<bool(double)>& member,
                  const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& refine) {
  auto dims = free_dims(box);
  const int m = static_cast<int>(dims.size());
  const Eigen::Index k = box.lower.size();
  std::vector<Eigen::VectorXd> members;
  members.push_back(opt.x);
  opt.sampled = 0;
  if (m > 0) {
    int per_dim = static_cast<int>(std::floor(std::pow(static_cast<double>(options.grid_budget), 1.0 / m)));
    per_dim = std::clamp(per_dim, 3, 401);
    std::vector<int> idx(m, 0);
    for (;;) {
      Eigen::VectorXd p = opt.x;
      for (int j = 0; j < m; ++j) {
        int i = dims[j];
        p[i] = box.lower[i] + (box.upper[i] - box.lower[i]) * idx[j] / (per_dim - 1);
      }
      ++opt.sampled;
      if (member(value_of(p))) members.push_back(p);
      int j = 0;
      while (j < m && ++idx[j] == per_dim) idx[j++] = 0;
      if (j == m) break;
    }
  }
  opt.set_size = static_cast<int>(members.size()) - 1;
  opt.set_lower = opt.x;
  opt.set_upper = opt.x;
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(k);
  for (const auto& p : members) {
    opt.set_lower = opt.set_lower.cwiseMin(p);
    opt.set_upper = opt.set_upper.cwiseMax(p);
    mean += p;
  }
  mean /= static_cast<double>(members.size());
  opt.principal_direction = Eigen::VectorXd::Zero(k);
  if (members.size() > 2) {
    Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(k, k);
    for (const auto& p : members) cov += (p - mean) * (p - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(cov);
    Eigen::VectorXd v = es.eigenvectors().col(k - 1);
    Eigen::Index imax;
    v.cwiseAbs().maxCoeff(&imax);
    opt.principal_direction = v[imax] < 0 ? Eigen::VectorXd(-v) : v;
  }
  // Farthest-point sampling from the optimum: each new representative is the member farthest
  // (in coded units) from those already chosen.
  opt.representatives = {opt.x};
  opt.representative_values = {value_of(opt.x)};
  std::vector<double> dist(members.size(), kInf);
  for (size_t i = 0; i < members.size(); ++i) dist[i] = (members[i] - opt.x).norm();
  while (static_cast<int>(opt.representatives.size()) < options.representatives) {
    size_t far = 0;
    for (size_t i = 1; i < members.size(); ++i)
      if (dist[i] > dist[far]) far = i;
    if (dist[far] <= 1e-12) break;
    const Eigen::VectorXd chosen = members[far];
    for (size_t i = 0; i < members.size(); ++i) dist[i] = std::min(dist[i], (members[i] - chosen).norm());
    Eigen::VectorXd r = refine ? refine(chosen) : chosen;
    opt.representatives.push_back(r);
    opt.representative_values.push_back(value_of(r));
  }
}

// Grid estimate of the response's range over the box, for the default tolerance.
double response_range(const Objective& f, const Box& box) {
  auto dims = free_dims(box);
  const int m = static_cast<int>(dims.size());
  if (m == 0) return 0;
  int per_dim = std::clamp(static_cast<int>(std::pow(4096.0, 1.0 / m)), 2, 64);
  double lo = kInf, hi = -kInf;
  std::vector<int> idx(m, 0);
  Eigen::VectorXd p = 0.5 * (box.lower + box.upper);
  for (;;) {
    for (int j = 0; j < m; ++j) {
      int i = dims[j];
      p[i] = box.lower[i] + (box.upper[i] - box.lower[i]) * idx[j] / (per_dim - 1);
    }
    double v = f(p);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    int j = 0;
    while (j < m && ++idx[j] == per_dim) idx[j++] = 0;
    if (j == m) break;
  }
  return hi - lo;
}

}  // namespace

std::string goal_name(const Goal& g) {
  switch (g.kind) {
    case GoalKind::minimize: return "minimize";
    case GoalKind::maximize: return "maximize";
    case GoalKind::target: {
      char buf[48];
      std::snprintf(buf, sizeof buf, "target %g", g.target);
      return buf;
    }
  }
  return "?";
}

Box Box::cube(int k, double h) {
  return Box{Eigen::VectorXd::Constant(k, -h), Eigen::VectorXd::Constant(k, h)};
}

void Box::fix(int factor, double v) {
  if (factor < 0 || factor >= lower.size()) throw StatsError("fixed factor out of range");
  lower[factor] = upper[factor] = v;
}

Optimum optimize(const Objective& response, const Box& box, const Goal& goal,
                 const OptimizeOptions& options) {
  check_box(box);
  Objective objective;
  switch (goal.kind) {
    case GoalKind::minimize: objective = response; break;
    case GoalKind::maximize: objective = [&](const Eigen::VectorXd& x) { return -response(x); }; break;
    case GoalKind::target:
      objective = [&](const Eigen::VectorXd& x) {
        double d = response(x) - goal.target;
        return d * d;
      };
      break;
  }
  Optimum opt;
  double best_objective;
  opt.x = multi_start(objective, box, options, best_objective);
  opt.value = response(opt.x);
  opt.tolerance = options.tolerance > 0 ? options.tolerance : 0.01 * response_range(response, box);
  const double tol = opt.tolerance;
  std::function<bool(double)> member;
  std::function<Eigen::VectorXd(const Eigen::VectorXd&)> refine;
  const double best = opt.value;
  switch (goal.kind) {
    case GoalKind::minimize: member = [=](double v) { return v <= best + tol; }; break;
    case GoalKind::maximize: member = [=](double v) { return v >= best - tol; }; break;
    case GoalKind::target: {
      double miss = std::fabs(best - goal.target);
      opt.target_reached = miss <= tol;
      double band = opt.target_reached ? tol : miss + tol;
      member = [=, t = goal.target](double v) { return std::fabs(v - t) <= band; };
      // Representatives of a target set are moved onto the contour response = target by a
      // few Newton steps along the (numerical) gradient, kept only if they get closer.
      refine = [&, t = goal.target](const Eigen::VectorXd& start) {
        Eigen::VectorXd x = start;
        for (int it = 0; it < 8; ++it) {
          double fx = response(x) - t;
          Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
          for (Eigen::Index i = 0; i < x.size(); ++i) {
            if (box.upper[i] == box.lower[i]) continue;
            double h = 1e-6 * (box.upper[i] - box.lower[i]);
            Eigen::VectorXd a = x, b = x;
            a[i] += h;
            b[i] -= h;
            g[i] = (response(a) - response(b)) / (2 * h);
          }
          double gg = g.squaredNorm();
          if (gg == 0) break;
          Eigen::VectorXd next = clamp(x - fx / gg * g, box);
          if (std::fabs(response(next) - t) >= std::fabs(fx)) break;
          x = next;
        }
        return x;
      };
      break;
    }
  }
  describe_set(opt, response, box, options, member, refine);
  return opt;
}

double desirability(double y, const DesirabilityGoal& g) {
  if (!(g.low < g.high)) throw StatsError("desirability: low must be below high");
  switch (g.kind) {
    case GoalKind::maximize:
      if (y <= g.low) return 0;
      if (y >= g.high) return 1;
      return std::pow((y - g.low) / (g.high - g.low), g.weight);
    case GoalKind::minimize:
      if (y <= g.low) return 1;
      if (y >= g.high) return 0;
      return std::pow((g.high - y) / (g.high - g.low), g.weight);
    case GoalKind::target:
      if (!(g.target >= g.low && g.target <= g.high))
        throw StatsError("desirability: the target must lie within [low, high]");
      if (y < g.low || y > g.high) return 0;
      if (y <= g.target)
        return g.target == g.low ? 1 : std::pow((y - g.low) / (g.target - g.low), g.weight);
      return g.target == g.high ? 1 : std::pow((g.high - y) / (g.high - g.target), g.weight);
  }
  return 0;
}

double overall_desirability(const std::vector<double>& y, const std::vector<DesirabilityGoal>& goals) {
  if (y.size() != goals.size() || goals.empty())
    throw StatsError("desirability: one goal per response is needed");
  double log_sum = 0, r_sum = 0;
  for (size_t i = 0; i < y.size(); ++i) {
    double d = desirability(y[i], goals[i]);
    if (d <= 0) return 0;
    log_sum += goals[i].importance * std::log(d);
    r_sum += goals[i].importance;
  }
  return std::exp(log_sum / r_sum);
}

Optimum optimize_desirability(const std::vector<Objective>& responses,
                              const std::vector<DesirabilityGoal>& goals, const Box& box,
                              const OptimizeOptions& options) {
  check_box(box);
  if (responses.size() != goals.size() || goals.empty())
    throw StatsError("desirability: one goal per response is needed");
  auto values = [&](const Eigen::VectorXd& x) {
    std::vector<double> y;
    for (const auto& r : responses) y.push_back(r(x));
    return y;
  };
  Objective overall = [&](const Eigen::VectorXd& x) { return overall_desirability(values(x), goals); };
  // Where D = 0 the surface is flat; the objective there is the summed (range-normalised)
  // distance of the responses from their acceptable ranges, so a search started there still
  // finds its way in. Any positive D ranks better than any violation.
  Objective objective = [&](const Eigen::VectorXd& x) {
    auto y = values(x);
    double d = overall_desirability(y, goals);
    if (d > 0) return -d;
    double violation = 0;
    for (size_t i = 0; i < y.size(); ++i) {
      const auto& g = goals[i];
      double span = g.high - g.low;
      double lo = g.low, hi = g.high;
      if (g.kind == GoalKind::maximize) hi = kInf;
      if (g.kind == GoalKind::minimize) lo = -kInf;
      if (y[i] < lo) violation += (lo - y[i]) / span;
      if (y[i] > hi) violation += (y[i] - hi) / span;
    }
    return 1e-12 + violation;  // > 0 even on the boundary of an acceptable range
  };
  Optimum opt;
  double best_objective;
  opt.x = multi_start(objective, box, options, best_objective);
  opt.value = overall(opt.x);
  opt.tolerance = options.tolerance > 0 ? options.tolerance : 0.01;
  const double best = opt.value, tol = opt.tolerance;
  describe_set(opt, overall, box, options, [=](double d) { return d > 0 && d >= best - tol; }, nullptr);
  return opt;
}

PointComparison compare_point(const Objective& response, const Goal& goal, const Optimum& best,
                              const Box& box, const Eigen::VectorXd& point) {
  PointComparison c;
  c.value = response(point);
  for (Eigen::Index i = 0; i < point.size(); ++i)
    if (point[i] < box.lower[i] - 1e-9 || point[i] > box.upper[i] + 1e-9) c.inside_box = false;
  switch (goal.kind) {
    case GoalKind::minimize: c.gap = c.value - best.value; break;
    case GoalKind::maximize: c.gap = best.value - c.value; break;
    case GoalKind::target:
      c.gap = std::fabs(c.value - goal.target) - std::fabs(best.value - goal.target);
      break;
  }
  c.in_near_set = c.inside_box && c.gap <= best.tolerance;
  return c;
}

}  // namespace repose::stats
