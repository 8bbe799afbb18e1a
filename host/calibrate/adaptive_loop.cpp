#include "calibrate/adaptive_loop.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "calibrate/campaign.h"
#include "stats/halton.h"
#include "stats/local_search.h"

namespace repose::calibrate {

namespace {

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

bool near_any(const Eigen::MatrixXd& done, const Eigen::VectorXd& p) {
  for (int i = 0; i < done.rows(); ++i)
    if ((done.row(i).transpose() - p).norm() < 1e-3) return true;
  return false;
}

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

// The probability that every response's mean lands within its tolerance at p (independent
// surrogates): the acquisition for several responses.
double probability_in_tolerance(const CampaignPlan& plan, const std::vector<ResponseModel>& models, const Eigen::VectorXd& p) {
  double prob = 1;
  for (const auto& m : models) {
    const PlanResponse& r = plan.responses[size_t(m.response)];
    const double mean = m.predict(p), sd = m.predict_sd(p), tol = r.absolute_tolerance();
    if (!(sd > 0)) prob *= std::abs(mean - r.measured) <= tol ? 1.0 : 0.0;
    else prob *= normal_cdf((r.measured + tol - mean) / sd) - normal_cdf((r.measured - tol - mean) / sd);
  }
  return prob;
}

// Where to run next when the answer is not yet on target: for one response the expected
// improvement towards the target, `best` the smallest |mean - target| of the surrogate at the
// runs so far (the plug-in rule for noisy responses); for several the probability that all land
// within tolerance. Unless repeats are allowed (each run its own packing seed), a point on top of
// an existing run is never proposed: it would give the same bytes.
Eigen::VectorXd propose(const CampaignPlan& plan, const std::vector<ResponseModel>& models, const Eigen::MatrixXd& done,
                        double& score_out) {
  const bool allow_repeat = plan.adaptive.seed_per_run;
  std::function<double(const Eigen::VectorXd&)> score;
  if (models.size() == 1) {
    const ResponseModel& m = models[0];
    const double target = plan.responses[size_t(m.response)].measured;
    double best = INFINITY;
    for (int i = 0; i < done.rows(); ++i) best = std::min(best, std::abs(m.predict(done.row(i).transpose()) - target));
    score = [&, best, target](const Eigen::VectorXd& p) {
      return expected_improvement_to_target(m.predict(p), m.predict_sd(p), target, best);
    };
  } else {
    score = [&](const Eigen::VectorXd& p) { return probability_in_tolerance(plan, models, p); };
  }
  return maximise(int(done.cols()), Eigen::MatrixXd(0, done.cols()),
                  [&](const Eigen::VectorXd& p) { return !allow_repeat && near_any(done, p) ? -1.0 : score(p); }, score_out);
}

// A surrogate's model of one response, for the rest of the campaign.
// The noise that sets the surrogate's sd is itself estimated, on `df` degrees of freedom of
// replicates: a variance estimate on df degrees of freedom is uncertain by sqrt(2 / df) of itself,
// so the sd is widened by sqrt(1 + 2 / df), the first-order predictive inflation (df / (df - 2)
// for large df). Measured on seeded trials with a 4-fill pilot (3 df): the posterior's 90 % region
// covered the truth in 90 % (1 factor) and 85 % (2 factors) of trials without it, 93-95 % with it.
double noise_df_factor(int df) { return df <= 0 ? 1.0 : std::sqrt(1.0 + 2.0 / df); }

ResponseModel surrogate_model(int response, const std::shared_ptr<GaussianProcess>& gp, int noise_df) {
  ResponseModel m;
  m.response = response;
  const double widen = noise_df_factor(noise_df);
  m.predict = [gp](const Eigen::VectorXd& c) { return gp->mean(c); };
  m.predict_sd = [gp, widen](const Eigen::VectorXd& c) { return widen * gp->sd(c); };
  m.surrogate_noise_sd = gp->noise_sd();
  return m;
}

}  // namespace

std::uint64_t loop_seed(const CampaignPlan& plan, int index) {
  return plan.seeds_follow_verification() ? plan.base_seed + std::uint64_t(plan.verification_runs) + std::uint64_t(index)
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

std::vector<RunSpec> pilot_runs(const CampaignPlan& plan) {
  std::vector<RunSpec> runs;
  const int k = int(plan.factors.size());
  for (int p = 0; p < (plan.adaptive.pilot > 0 ? plan.adaptive.pilot_points : 0); ++p) {
    const double c = plan.adaptive.pilot_points == 1 ? 0.0 : (p == 0 ? -0.5 : 0.5);
    const std::vector<double> x = to_actual(plan, Eigen::VectorXd::Constant(k, c));
    for (int r = 0; r < plan.adaptive.pilot; ++r) {
      // Seeds far from the loop's and the verification's (base + 1 ...), so no packing repeats.
      const std::uint64_t seed = plan.base_seed + 500000 + std::uint64_t(1000 * p + r);
      runs.push_back({"pilot-" + std::to_string(p + 1) + "-r" + std::to_string(r), "pilot", p + 1, r, seed, x});
    }
  }
  return runs;
}

std::vector<RunSpec> adaptive_verification_runs(const CampaignPlan& plan, const std::vector<double>& x, int loop_runs,
                                                int round) {
  std::vector<RunSpec> runs;
  char id[48];
  const std::uint64_t first = round == 0 ? 0 : 900000 + 1000 * std::uint64_t(round);
  for (int r = 1; r <= plan.verification_runs; ++r) {
    std::snprintf(id, sizeof id, "verify-%03d-r%d", loop_runs, r);
    runs.push_back({id, "verify", 0, r, plan.base_seed + first + std::uint64_t(r), x});
  }
  return runs;
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

LoopDecision decide(const CampaignPlan& plan, const std::vector<Observations>& obs, const std::vector<NoiseEstimate>& noise) {
  LoopDecision d;
  for (size_t i = 0; i < obs.size(); ++i) {
    NoiseBounds bounds;
    if (noise[i].known()) bounds = {noise[i].low, noise[i].high};
    d.gps.push_back(std::make_shared<GaussianProcess>(fit_gaussian_process(obs[i].x, obs[i].y, bounds)));
    d.models.push_back(surrogate_model(obs[i].response, d.gps.back(), noise[i].df));
  }
  const Eigen::MatrixXd& x = obs.front().x;
  const int k = int(x.cols());
  double top = 0;
  // The best estimate: the smallest expected squared miss of the mean responses (the runs' own
  // points are candidates too).
  d.chosen = maximise(k, x, [&](const Eigen::VectorXd& p) { return -expected_miss(plan, d.models, p); }, top);
  // Met when every surrogate mean at the best estimate lies within its tolerance of the target
  // and is itself known to within it (one sd): a lucky single run of a noisy response does not
  // stop the loop, and a noise-free run on target does (its sd is ~0).
  const bool on_target = within_tolerance(plan, d.models, d.chosen);
  // A surrogate on fewer runs than a plane and two more has no credible uncertainty yet (three
  // runs in two factors fit any smooth surface): it cannot stop the loop.
  d.met = on_target && x.rows() >= k + 3;
  for (const auto& m : d.models) d.met = d.met && m.predict_sd(d.chosen) <= plan.responses[size_t(m.response)].absolute_tolerance();
  if (plan.adaptive.seed_per_run && on_target) {
    d.next = d.chosen;  // on target but not yet sure of it: another packing there narrows the sd
    d.repeat = true;
  } else {
    d.next = propose(plan, d.models, x, d.expected_improvement);
  }
  return d;
}

namespace {

// Each calibrating response at the given points, and its noise from the replicates among them.
void observe_all(const CampaignPlan& plan, const RunSource& source, const std::vector<RunSpec>& points,
                 std::vector<Observations>& obs, std::vector<NoiseEstimate>& noise) {
  obs.clear();
  noise.clear();
  for (int r : plan.calibration_responses()) {
    obs.push_back(observe(plan, source, points, r));
    noise.push_back(pooled_noise(replicate_groups(obs.back())));
  }
}

// The surrogates in words for the report: kernels, what they expect at the chosen point, the
// noise they settled on against the replicates' own, and what pinning the mean down would take.
std::string surrogate_text(const CampaignPlan& plan, const LoopDecision& d, const CalibrationResult& res, int count) {
  std::ostringstream text;
  for (size_t i = 0; i < d.gps.size(); ++i) {
    const GaussianProcess& gp = *d.gps[i];
    const ResponseModel& m = res.models[i];
    const PlanResponse& r = plan.responses[size_t(m.response)];
    const double tol = r.absolute_tolerance();
    text << "Gaussian process of " << r.label << " on " << gp.x.rows() << " runs (" << count << " of the loop): "
         << (gp.trend ? "linear trend + " : "") << "squared-exponential kernel, length scales (coded units)";
    for (size_t j = 0; j < plan.factors.size(); ++j) text << " " << plan.factors[j].name << " = " << gp.length_scale[int(j)];
    text << ", signal sd = " << gp.y_scale * std::sqrt(gp.signal_variance) << ", noise sd = " << gp.noise_sd()
         << ", restricted log likelihood = " << gp.log_likelihood << "\n";
    text << "At the chosen point the surrogate's mean " << r.name << " is " << m.predicted << " +- " << m.predicted_sd
         << " (sd of the mean). Tolerance " << tol << ".\n";
    if (m.noise.known())
      text << "Replicates: noise sd " << m.noise.sd << " on " << m.noise.df << " df (95 % interval " << m.noise.low << " .. "
           << m.noise.high << ")" << (plan.adaptive.seed_per_run ? "; the surrogate's noise is held inside it" : "") << ".\n";
    const double noise_sd = m.noise.known() ? m.noise.sd : gp.noise_sd();
    if (noise_sd > tol)
      text << "At this noise, knowing the mean to within the tolerance takes about (" << noise_sd << " / " << tol
           << ")^2 = " << runs_for_standard_error(noise_sd, tol) << " runs at the point.\n";
  }
  return text.str();
}

// The surrogates at the loop's choice, with the replicates' noise: what a verification weighs.
CalibrationResult loop_models(const LoopDecision& d, const std::vector<Observations>& obs,
                              const std::vector<NoiseEstimate>& noise) {
  CalibrationResult res;
  res.method = "adaptive (Gaussian process + expected improvement)";
  res.chosen_coded = d.chosen;
  res.models = d.models;
  for (size_t i = 0; i < res.models.size(); ++i) {
    ResponseModel& m = res.models[i];
    m.noise = noise[i];
    m.runs = obs[i].runs;
    m.predicted = m.predict(d.chosen);
    m.predicted_sd = m.predict_sd(d.chosen);
  }
  res.model_on_target = d.met;
  return res;
}

// The calibration the loop's last decision gives: the surrogates, the parameters and the posterior.
CalibrationResult loop_result(const CampaignPlan& plan, const LoopDecision& d, const std::vector<Observations>& obs,
                              const std::vector<NoiseEstimate>& noise, int count) {
  CalibrationResult res = loop_models(d, obs, noise);
  describe_parameters(plan, res);
  add_posterior(plan, res);
  res.model_text = surrogate_text(plan, d, res, count);
  return res;
}

void print_progress(const CampaignPlan& plan, const LoopDecision& d) {
  std::string s;
  for (const auto& m : d.models) {
    const PlanResponse& r = plan.responses[size_t(m.response)];
    char buf[320];
    std::snprintf(buf, sizeof buf, "%s%s = %.6g +- %.3g (target %.6g, tolerance %.3g, surrogate noise sd %.3g; next %.6g +- %.3g)",
                  s.empty() ? "" : "; ", r.label.c_str(), m.predict(d.chosen), m.predict_sd(d.chosen), r.measured,
                  r.absolute_tolerance(), m.surrogate_noise_sd, m.predict(d.next), m.predict_sd(d.next));
    s += buf;
  }
  std::fprintf(stderr, "loop: surrogate at its best estimate: %s%s\n", s.c_str(), d.repeat ? "; repeating it with a new packing" : "");
}


// A verification can check the surrogate before the budget only when its runs can train it:
// each calibrating rig is verified (a box calibrated and a cylinder verified is a check of the
// transfer, made once, at the end) and each run packs its own seed.
bool verifies_surrogate(const CampaignPlan& plan) {
  if (!plan.adaptive.seed_per_run) return false;
  const std::vector<int> verified = plan.rigs_of(plan.verified_responses());
  for (int rig : plan.rigs_of(plan.calibration_responses()))
    if (std::find(verified.begin(), verified.end(), rig) == verified.end()) return false;
  return true;
}

// True when a campaign with a smaller budget ended at this loop length and verified its choice
// (the same point: each decision depends only on the runs before it). A raised budget resumes
// past it, and its runs, already paid for, count as a round like any other.
bool verified_before(const CampaignPlan& plan, const RunSource& source, const LoopDecision& d, int count, int round) {
  const std::vector<RunSpec> runs = adaptive_verification_runs(plan, to_actual(plan, d.chosen), count, round);
  const std::vector<int> rigs = plan.rigs_of(plan.verified_responses());
  return !runs.empty() && !rigs.empty() && source.find(rig_run_id(plan, runs.front().id, rigs.front())) != nullptr;
}

// Verifies the surrogate's choice mid-loop: true when confirmed; otherwise the round is kept
// (its runs then train the surrogate).
bool verify_mid_loop(const CampaignPlan& plan, RunSource& source, const LoopDecision& d, const std::vector<Observations>& obs,
                     const std::vector<NoiseEstimate>& noise, int count, bool quiet, AdaptiveOutcome& out) {
  VerificationRound round;
  round.loop_runs = count;
  round.budget_end = !d.met;
  round.runs = adaptive_verification_runs(plan, to_actual(plan, d.chosen), count, int(out.rounds.size()));
  CalibrationResult res = loop_models(d, obs, noise);  // no posterior: only the verdict is kept
  verify_result(plan, source, round.runs, res);
  if (res.target_reached) return true;
  round.checks = res.checks;
  if (!quiet)
    std::fprintf(stderr, "loop: the verification after loop run %d%s did not confirm the surrogate (%s); its runs join the surrogate's data\n",
                 count, round.budget_end ? " (where a smaller budget ended)" : "",
                 res.checks.empty() ? "nothing verified" : agreement_name(res.checks.front().agreement));
  out.rounds.push_back(round);
  return false;
}

}  // namespace

AdaptiveOutcome run_adaptive(const CampaignPlan& plan, RunSource& source, bool quiet) {
  AdaptiveOutcome out;
  out.initial = plan.adaptive.initial;
  const std::vector<int> rigs = plan.rigs_of(plan.calibration_responses());
  const std::vector<RunSpec> pilot = pilot_runs(plan);
  source.run(on_rigs(plan, pilot, rigs), "noise pilot");
  std::vector<RunSpec> points = adaptive_start_runs(plan);
  source.run(on_rigs(plan, points, rigs), "loop start");
  std::vector<double> proposal_ei(points.size(), 0.0);
  // Runs with their own seeds are independent noise: the pilot's replicates join the loop's runs
  // and bound the surrogate's noise. With one seed for all, the loop's runs are a smooth function
  // of the factors and the pilot only measures the packing noise for the verification.
  std::vector<Observations> obs, pilot_obs;
  std::vector<NoiseEstimate> noise, pilot_noise;
  observe_all(plan, source, pilot, pilot_obs, pilot_noise);
  LoopDecision d;
  const auto train = [&] {
    std::vector<RunSpec> training = points;
    if (plan.adaptive.seed_per_run) training.insert(training.begin(), pilot.begin(), pilot.end());
    for (const auto& round : out.rounds) training.insert(training.end(), round.runs.begin(), round.runs.end());
    observe_all(plan, source, training, obs, noise);
    d = decide(plan, obs, plan.adaptive.seed_per_run ? noise : std::vector<NoiseEstimate>(noise.size()));
  };
  const bool verifies = verifies_surrogate(plan);
  for (;;) {
    train();
    const int count = int(points.size());
    if (d.met && out.simulations_to_target < 0) out.simulations_to_target = count;
    if (count >= plan.adaptive.budget) break;
    // With one seed for all, a verification at the same point would repeat the loop's own runs;
    // on another rig it cannot train the surrogate: the loop ends where the surrogate is sure.
    if (d.met && !verifies) break;
    if (verifies && (d.met || verified_before(plan, source, d, count, int(out.rounds.size())))) {
      if (verify_mid_loop(plan, source, d, obs, noise, count, quiet, out)) break;
      train();
    }
    if (!quiet) print_progress(plan, d);
    RunSpec spec{loop_id(count + 1), "loop", count + 1, 0, loop_seed(plan, count + 1), to_actual(plan, d.next)};
    source.run(on_rigs(plan, {spec}, rigs), "loop");
    points.push_back(spec);
    proposal_ei.push_back(d.expected_improvement);
  }
  const std::vector<NoiseEstimate>& reported = plan.adaptive.seed_per_run ? noise : pilot_noise;
  std::vector<Observations> loop_obs;
  std::vector<NoiseEstimate> loop_noise;
  observe_all(plan, source, points, loop_obs, loop_noise);
  for (size_t i = 0; i < points.size(); ++i) {
    LoopStep step;
    step.run = loop_obs[0].runs[i];
    for (const auto& o : loop_obs) step.values.push_back(o.y[int(i)]);
    const double measured = plan.primary().measured;
    step.relative_error = (step.values[0] - measured) / measured;
    step.expected_improvement = proposal_ei[i];
    out.steps.push_back(step);
  }
  if (!pilot_obs.empty()) out.pilot = pilot_obs[0].runs;
  out.result = loop_result(plan, d, obs, reported, int(points.size()));
  return out;
}

}  // namespace repose::calibrate
