#include "calibrate/adaptive_loop.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "calibrate/design_runs.h"
#include "calibrate/gaussian_process.h"
#include "stats/halton.h"
#include "stats/local_search.h"

namespace repose::calibrate {

namespace {

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

// Maximises `score` over the given points and quasi-random candidates, then polishes the best by
// a shrinking compass search inside the coded cube.
Eigen::VectorXd maximise(int k, const Eigen::MatrixXd& extra, const std::function<double(const Eigen::VectorXd&)>& score,
                         double& top) {
  std::vector<Eigen::VectorXd> candidates;
  for (int i = 0; i < extra.rows(); ++i) candidates.push_back(extra.row(i).transpose());
  for (const auto& p : halton_points(k, 1, 1024 * k)) candidates.push_back(p);
  return stats::compass_maximise(score, candidates, top);
}

// Expected improvement towards the target, `best` the smallest |mean - target| at the runs so far
// (the surrogate's mean, not the noisy runs themselves: the plug-in rule for noisy responses).
// Unless repeats are allowed (each run its own packing seed), a point on top of an existing run
// is never proposed: it would give the same bytes.
Eigen::VectorXd propose(const GaussianProcess& gp, double target, double best, const Eigen::MatrixXd& done,
                        bool allow_repeat, double& ei_out) {
  auto too_close = [&](const Eigen::VectorXd& p) {
    for (int i = 0; i < done.rows(); ++i)
      if ((done.row(i).transpose() - p).norm() < 1e-3) return true;
    return false;
  };
  auto ei = [&](const Eigen::VectorXd& p) {
    return !allow_repeat && too_close(p) ? -1.0 : expected_improvement_to_target(gp.mean(p), gp.sd(p), target, best);
  };
  return maximise(int(done.cols()), Eigen::MatrixXd(0, done.cols()), ei, ei_out);
}

// The surrogate's answer: where the expected squared distance of the mean response from the
// target, (mean - target)^2 + sd^2, is smallest (the runs' own points are candidates too).
Eigen::VectorXd best_estimate(const GaussianProcess& gp, double target, const Eigen::MatrixXd& done) {
  double top = 0;
  return maximise(int(done.cols()), done, [&](const Eigen::VectorXd& p) {
    const double d = gp.mean(p) - target, s = gp.sd(p);
    return -(d * d + s * s);
  }, top);
}

// The run-to-run noise the surrogate found (its nugget), in the response's units.
double noise_sd(const GaussianProcess& gp) {
  return gp.y_scale * std::sqrt(gp.signal_variance * gp.noise_ratio);
}

}  // namespace

std::uint64_t loop_seed(const CampaignPlan& plan, int index) {
  return plan.adaptive.seed_per_run ? plan.base_seed + std::uint64_t(plan.verification_runs) + std::uint64_t(index)
                                    : plan.base_seed;
}

std::vector<RunSpec> adaptive_start_runs(const CampaignPlan& plan) {
  std::vector<RunSpec> start;
  int index = 0;
  for (const auto& p : halton_points(int(plan.factors.size()), 1, plan.adaptive.initial)) {
    ++index;
    start.push_back({loop_id(index), "loop", index, 0, loop_seed(plan, index), to_actual(plan, p)});
  }
  return start;
}

std::vector<Eigen::VectorXd> halton_points(int k, int first, int count) {
  static const int primes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37};
  if (k > 12) throw std::runtime_error("the adaptive loop takes at most 12 factors");
  std::vector<Eigen::VectorXd> pts;
  for (int i = first; i < first + count; ++i) {
    Eigen::VectorXd p(k);
    for (int d = 0; d < k; ++d) p[d] = 2 * stats::radical_inverse(i, primes[d]) - 1;
    pts.push_back(p);
  }
  return pts;
}

LoopDecision decide(const CampaignPlan& plan, const Eigen::MatrixXd& x, const Eigen::VectorXd& y) {
  const double target = plan.measured, tol = plan.absolute_tolerance();
  LoopDecision d;
  d.gp = std::make_shared<GaussianProcess>(fit_gaussian_process(x, y));
  const GaussianProcess& gp = *d.gp;
  d.chosen = best_estimate(gp, target, x);
  d.mean = gp.mean(d.chosen);
  d.sd = gp.sd(d.chosen);
  d.noise_sd = noise_sd(gp);
  // Met when the surrogate's mean response at its best estimate lies within the tolerance of the
  // target and is itself known to within the tolerance (one sd): a lucky single run of a noisy
  // response does not stop the loop, and a noise-free run on target does (its sd is ~0).
  const bool on_target = std::abs(d.mean - target) <= tol;
  d.met = on_target && d.sd <= tol;
  if (plan.adaptive.seed_per_run && on_target) {
    d.next = d.chosen;  // on target but not yet sure of it: another packing there narrows the sd
    d.repeat = true;
  } else {
    double best = INFINITY;
    for (int i = 0; i < x.rows(); ++i) best = std::min(best, std::abs(gp.mean(x.row(i).transpose()) - target));
    d.next = propose(gp, target, best, x, plan.adaptive.seed_per_run, d.expected_improvement);
  }
  return d;
}

namespace {

// The loop's runs 1..count from the store: coded factors x, responses y, and the records.
void gather_loop_runs(const CampaignPlan& plan, RunStore& store, int count, Eigen::MatrixXd& x, Eigen::VectorXd& y,
                      std::vector<RunRecord>& runs) {
  x.resize(count, int(plan.factors.size()));
  y.resize(count);
  runs.clear();
  for (int i = 1; i <= count; ++i) {
    const RunRecord* r = store.find(loop_id(i));
    if (!r) throw std::runtime_error(loop_id(i) + " is missing from " + store.path());
    runs.push_back(*r);
    x.row(i - 1) = to_coded(plan, r->spec.x).transpose();
    y[i - 1] = r->responses.at(plan.response);
  }
}

// The surrogate in words for the report: its kernel, what it expects at the chosen point, and
// how many runs the noise would take to pin the mean down.
std::string surrogate_text(const CampaignPlan& plan, const GaussianProcess& gp, const CalibrationResult& res, int count) {
  const double tol = plan.absolute_tolerance();
  std::ostringstream text;
  text << "Gaussian process on " << count << " runs: squared-exponential kernel, length scales (coded units)";
  for (size_t j = 0; j < plan.factors.size(); ++j) text << " " << plan.factors[j].name << " = " << gp.length_scale[j];
  text << ", nugget/signal variance = " << gp.noise_ratio << ", signal sd = " << gp.y_scale * std::sqrt(gp.signal_variance)
       << ", log marginal likelihood = " << gp.log_likelihood << "\n";
  text << "At the chosen point the surrogate's mean " << plan.response << " is " << res.predicted << " +- " << res.predicted_sd
       << " (sd of the mean); run-to-run noise sd " << res.run_noise_sd << " (the nugget). Tolerance " << tol << ".\n";
  if (res.run_noise_sd > tol)
    text << "At this noise, knowing the mean to within the tolerance takes about (" << res.run_noise_sd << " / " << tol
         << ")^2 = " << std::ceil(std::pow(res.run_noise_sd / tol, 2)) << " runs at the point.\n";
  return text.str();
}

// The calibration the loop's last decision gives: the chosen point, the surrogate's prediction
// there, each factor's slope and the box of sampled points the surrogate puts on target.
CalibrationResult loop_result(const CampaignPlan& plan, const LoopDecision& d, int count) {
  const int k = int(plan.factors.size());
  const double target = plan.measured, tol = plan.absolute_tolerance();
  const std::shared_ptr<GaussianProcess> gp = d.gp;
  const Eigen::VectorXd chosen = d.chosen;
  CalibrationResult res;
  res.method = "adaptive (Gaussian process + expected improvement)";
  res.chosen_coded = chosen;
  res.chosen = to_actual(plan, chosen);
  res.predicted = d.mean;
  res.predicted_sd = d.sd;
  res.run_noise_sd = d.noise_sd;
  res.target_reached = d.met;
  res.predict = [gp](const Eigen::VectorXd& c) { return gp->mean(c); };
  res.predict_sd = [gp](const Eigen::VectorXd& c) { return gp->sd(c); };
  Eigen::VectorXd grad = gp->gradient(chosen);
  Eigen::VectorXd lo = chosen, hi = chosen;
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
  res.model_text = surrogate_text(plan, *gp, res, count);
  return res;
}

}  // namespace

AdaptiveOutcome run_adaptive(const CampaignPlan& plan, RunStore& store, Executor& executor, bool quiet) {
  const double target = plan.measured, tol = plan.absolute_tolerance();
  AdaptiveOutcome out;
  out.initial = plan.adaptive.initial;
  std::vector<RunSpec> start = adaptive_start_runs(plan);
  executor.run(start, "loop start");
  std::vector<double> proposal_ei(start.size(), 0.0);

  Eigen::MatrixXd x;
  Eigen::VectorXd y;
  std::vector<RunRecord> runs;
  int count = int(start.size());
  LoopDecision d;
  for (;;) {
    gather_loop_runs(plan, store, count, x, y, runs);
    d = decide(plan, x, y);
    if (d.met && out.simulations_to_target < 0) out.simulations_to_target = count;
    if (d.met || count >= plan.adaptive.budget) break;
    const Eigen::VectorXd& next = d.next;
    const double ei = d.expected_improvement;
    RunSpec spec{loop_id(count + 1), "loop", count + 1, 0, loop_seed(plan, count + 1), to_actual(plan, next)};
    if (const RunRecord* stored = store.find(spec.id); stored && stored->spec.x != spec.x)
      throw std::runtime_error(store.path() + " holds a " + spec.id + " at other parameters than the loop proposes now; "
                               "start again with --new");
    if (!quiet) {
      std::fprintf(stderr,
                   "loop: surrogate %s = %.6g +- %.3g at its best estimate (target %.6g, tolerance %.3g, run noise sd %.3g); "
                   "next: mean %.6g +- %.3g, EI %.3g\n",
                   plan.response.c_str(), d.mean, d.sd, target, tol, d.noise_sd, d.gp->mean(next), d.gp->sd(next), ei);
    }
    executor.run({spec}, "loop");
    proposal_ei.push_back(ei);
    ++count;
  }
  for (int i = 0; i < count; ++i)
    out.steps.push_back({runs[i], (y[i] - target) / target, i < int(proposal_ei.size()) ? proposal_ei[i] : 0.0});
  out.result = loop_result(plan, d, count);
  return out;
}

}  // namespace repose::calibrate
