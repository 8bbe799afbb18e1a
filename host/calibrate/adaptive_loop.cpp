#include "calibrate/adaptive_loop.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "calibrate/design_runs.h"
#include "calibrate/gaussian_process.h"

namespace repose::calibrate {

namespace {

double radical_inverse(int index, int base) {
  double f = 1, r = 0;
  for (int i = index; i > 0; i /= base) {
    f /= base;
    r += f * (i % base);
  }
  return r;
}

std::vector<double> to_actual(const CampaignPlan& plan, const Eigen::VectorXd& coded) {
  std::vector<double> x;
  for (int j = 0; j < coded.size(); ++j) {
    const auto& f = plan.factors[j];
    x.push_back(0.5 * (f.low + f.high) + coded[j] * 0.5 * (f.high - f.low));
  }
  return x;
}

Eigen::VectorXd to_coded(const CampaignPlan& plan, const std::vector<double>& x) {
  Eigen::VectorXd c(x.size());
  for (size_t j = 0; j < x.size(); ++j) {
    const auto& f = plan.factors[j];
    c[j] = (x[j] - 0.5 * (f.low + f.high)) / (0.5 * (f.high - f.low));
  }
  return c;
}

std::string loop_id(int index) {
  char id[32];
  std::snprintf(id, sizeof id, "loop-%03d", index);
  return id;
}

// Maximises expected improvement over quasi-random candidates, then polishes the best by a
// shrinking compass search; a point on top of an existing run is never proposed.
Eigen::VectorXd propose(const GaussianProcess& gp, double target, double best, const Eigen::MatrixXd& done, double& ei_out) {
  const int k = int(done.cols());
  auto too_close = [&](const Eigen::VectorXd& p) {
    for (int i = 0; i < done.rows(); ++i)
      if ((done.row(i).transpose() - p).norm() < 1e-3) return true;
    return false;
  };
  auto ei = [&](const Eigen::VectorXd& p) {
    return too_close(p) ? -1.0 : expected_improvement_to_target(gp.mean(p), gp.sd(p), target, best);
  };
  Eigen::VectorXd arg;
  double top = -INFINITY;
  for (const auto& p : halton_points(k, 1, 1024 * k)) {
    double v = ei(p);
    if (v > top) {
      top = v;
      arg = p;
    }
  }
  for (double step = 0.05; step > 1e-4; step *= 0.5) {
    bool moved = true;
    while (moved) {
      moved = false;
      for (int d = 0; d < k; ++d)
        for (double dir : {-1.0, 1.0}) {
          Eigen::VectorXd p = arg;
          p[d] = std::clamp(p[d] + dir * step, -1.0, 1.0);
          double v = ei(p);
          if (v > top + 1e-15) {
            top = v;
            arg = p;
            moved = true;
          }
        }
    }
  }
  ei_out = top;
  return arg;
}

}  // namespace

std::vector<Eigen::VectorXd> halton_points(int k, int first, int count) {
  static const int primes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37};
  if (k > 12) throw std::runtime_error("the adaptive loop takes at most 12 factors");
  std::vector<Eigen::VectorXd> pts;
  for (int i = first; i < first + count; ++i) {
    Eigen::VectorXd p(k);
    for (int d = 0; d < k; ++d) p[d] = 2 * radical_inverse(i, primes[d]) - 1;
    pts.push_back(p);
  }
  return pts;
}

AdaptiveOutcome run_adaptive(const CampaignPlan& plan, RunStore& store, Executor& executor, bool quiet) {
  const int k = int(plan.factors.size());
  const double target = plan.measured, tol = plan.absolute_tolerance();
  AdaptiveOutcome out;
  out.initial = plan.adaptive.initial;
  std::vector<RunSpec> start;
  std::vector<double> start_ei;
  int index = 0;
  for (const auto& p : halton_points(k, 1, plan.adaptive.initial))
    start.push_back({loop_id(++index), "loop", index, 0, plan.base_seed, to_actual(plan, p)});
  executor.run(start, "loop start");
  std::vector<double> proposal_ei(start.size(), 0.0);

  auto gather = [&](int count, Eigen::MatrixXd& x, Eigen::VectorXd& y, std::vector<RunRecord>& runs) {
    x.resize(count, k);
    y.resize(count);
    runs.clear();
    for (int i = 1; i <= count; ++i) {
      const RunRecord* r = store.find(loop_id(i));
      if (!r) throw std::runtime_error(loop_id(i) + " is missing from " + store.path());
      runs.push_back(*r);
      x.row(i - 1) = to_coded(plan, r->spec.x).transpose();
      y[i - 1] = r->responses.at(plan.response);
    }
  };
  Eigen::MatrixXd x;
  Eigen::VectorXd y;
  std::vector<RunRecord> runs;
  int count = int(start.size());
  for (;;) {
    gather(count, x, y, runs);
    int best = 0;
    for (int i = 0; i < count; ++i) {
      if (std::abs(y[i] - target) < std::abs(y[best] - target)) best = i;
      if (out.simulations_to_target < 0 && std::abs(y[i] - target) <= tol) out.simulations_to_target = i + 1;
    }
    if (std::abs(y[best] - target) <= tol || count >= plan.adaptive.budget) break;
    GaussianProcess gp = fit_gaussian_process(x, y);
    double ei = 0;
    Eigen::VectorXd next = propose(gp, target, std::abs(y[best] - target), x, ei);
    RunSpec spec{loop_id(count + 1), "loop", count + 1, 0, plan.base_seed, to_actual(plan, next)};
    if (const RunRecord* stored = store.find(spec.id); stored && stored->spec.x != spec.x)
      throw std::runtime_error(store.path() + " holds a " + spec.id + " at other parameters than the loop proposes now; "
                               "start again with --new");
    if (!quiet) {
      std::fprintf(stderr, "loop: best |%s - %.6g| = %.3g (tolerance %.3g); GP mean at proposal %.6g +- %.3g, EI %.3g\n",
                   plan.response.c_str(), target, std::abs(y[best] - target), tol, gp.mean(next), gp.sd(next), ei);
    }
    executor.run({spec}, "loop");
    proposal_ei.push_back(ei);
    ++count;
  }
  for (int i = 0; i < count; ++i)
    out.steps.push_back({runs[i], (y[i] - target) / target, i < int(proposal_ei.size()) ? proposal_ei[i] : 0.0});

  int best = 0;
  for (int i = 0; i < count; ++i)
    if (std::abs(y[i] - target) < std::abs(y[best] - target)) best = i;
  auto gp = std::make_shared<GaussianProcess>(fit_gaussian_process(x, y));
  CalibrationResult& res = out.result;
  res.method = "adaptive (Gaussian process + expected improvement)";
  res.chosen = runs[best].spec.x;
  res.chosen_coded = x.row(best).transpose();
  res.predicted = gp->mean(res.chosen_coded);
  res.target_reached = std::abs(y[best] - target) <= tol;
  res.predict = [gp](const Eigen::VectorXd& c) { return gp->mean(c); };
  res.predict_sd = [gp](const Eigen::VectorXd& c) { return gp->sd(c); };
  Eigen::VectorXd grad = gp->gradient(res.chosen_coded);
  Eigen::VectorXd lo = res.chosen_coded, hi = res.chosen_coded;
  for (const auto& p : halton_points(k, 1, 4096))
    if (std::abs(gp->mean(p) - target) <= tol) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  std::vector<double> lo_a = to_actual(plan, lo), hi_a = to_actual(plan, hi);
  for (int j = 0; j < k; ++j) {
    const auto& f = plan.factors[j];
    res.parameters.push_back({f.name, res.chosen[j], grad[j] / (0.5 * (f.high - f.low)), 0, lo_a[j], hi_a[j]});
  }
  std::ostringstream text;
  text << "Gaussian process on " << count << " runs: squared-exponential kernel, length scales (coded units)";
  for (int j = 0; j < k; ++j) text << " " << plan.factors[j].name << " = " << gp->length_scale[j];
  text << ", nugget/signal variance = " << gp->noise_ratio << ", signal sd = " << gp->y_scale * std::sqrt(gp->signal_variance)
       << ", log marginal likelihood = " << gp->log_likelihood << "\n";
  res.model_text = text.str();
  return out;
}

}  // namespace repose::calibrate
