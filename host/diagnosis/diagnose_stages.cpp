#include "diagnosis/diagnose_stages.h"
#include "diagnosis/measured_data.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "experiments/repose.h"
#include "stats/fdist.h"

namespace repose {

namespace {

constexpr double kAicClose = 2.0;       // Burnham & Anderson: models within 2 have equal support
constexpr double kAicRejected = 10.0;   // ... and one more than 10 above the best has essentially none

double two_sided_normal_p(double z) { return std::erfc(std::abs(z) / std::sqrt(2.0)); }

// Weighted least-squares slope of residuals on x (weights 1/var, variances known from the
// replicate scatter): slope, its standard error, z and p.
Trend slope_of(const std::vector<double>& x, const std::vector<double>& r, const std::vector<double>& w) {
  Trend t;
  double sw = 0, swx = 0;
  for (size_t k = 0; k < x.size(); ++k) { sw += w[k]; swx += w[k] * x[k]; }
  double xbar = swx / sw, sxx = 0, sxr = 0;
  for (size_t k = 0; k < x.size(); ++k) {
    sxx += w[k] * (x[k] - xbar) * (x[k] - xbar);
    sxr += w[k] * (x[k] - xbar) * r[k];
  }
  if (!(sxx > 0)) return t;
  t.slope = sxr / sxx;
  t.se = 1.0 / std::sqrt(sxx);
  t.z = t.slope / t.se;
  t.p = two_sided_normal_p(t.z);
  return t;
}

// Why an extension cannot be tested on these data; empty when it can.
std::string untestable_reason(const ModelExtension& e, const Observations& obs, bool scatter_scored) {
  bool revealed = false;
  for (const auto& m : obs.measures)
    revealed = revealed || std::find(e.revealed_by.begin(), e.revealed_by.end(), m) != e.revealed_by.end();
  if (!e.apply) return e.pending_reason;
  if (!revealed) {
    std::string shows;
    for (const auto& m : e.revealed_by) shows += (shows.empty() ? "" : ", ") + m;
    return "none of the measured quantities responds to it (it shows in " + shows + ")";
  }
  if (e.needs_sigma && !scatter_scored)
    return "its signature is the replicate scatter, which without a sigma column (the measurement error) is taken "
           "as the noise: give sigma to test it";
  return "";
}

// Two fitted heap models compared on every heap measure, measured or not (a simulated heap gives
// them all): the one where their means over the conditions differ most, in SDs of one simulated
// heap. Bed heights alone simulate no heap: then the heap after the lift is what to measure.
Separation heap_separation(DiagnosisContext& c, const ModelResult& best, const ModelResult& second) {
  const Observations& obs = c.obs;
  Separation s;
  if (std::all_of(obs.measures.begin(), obs.measures.end(), [](const std::string& m) { return m == "bed_height"; })) {
    s.kind = Separation::Kind::HeapAfterLift;
    return s;
  }
  // Both fitted models' fresh replicates (simulated for their scores).
  int first = c.predictor.confirmation_first(), reps = c.predictor.confirmation_replicates();
  for (const std::string& m : heap_measure_names()) {
    double difference = 0, variance = 0;
    for (size_t k = 0; k < obs.conditions.size(); ++k) {
      double mean[2] = {0, 0}, square[2] = {0, 0};
      const ModelResult* models[2] = {&best, &second};
      for (int i = 0; i < 2; ++i)
        for (int r = first; r < first + reps; ++r) {
          double v = c.predictor.simulate(k, find_extension(models[i]->id), models[i]->params, r).values.at(m);
          mean[i] += v / reps;
          square[i] += v * v / reps;
        }
      difference += (mean[0] - mean[1]) / double(obs.conditions.size());
      for (int i = 0; i < 2; ++i)
        variance += (square[i] - mean[i] * mean[i]) * reps / (reps - 1) / (2.0 * double(obs.conditions.size()));
    }
    double sds = variance > 0 ? std::abs(difference) / std::sqrt(variance) : 0;
    if (sds > s.heap_sds) {
      s.heap_sds = sds;
      s.measure = m;
      s.largest_difference = std::abs(difference);
    }
  }
  s.kind = s.heap_sds >= 1 ? Separation::Kind::HeapMeasure : Separation::Kind::SecondRig;
  return s;
}

// Which measurement would tell the winner from its closest rival.
Separation separation_of(DiagnosisContext& c, const ModelResult& best, const ModelResult& second) {
  const Observations& obs = c.obs;
  Separation s;
  size_t far = obs.conditions.size() - 1;
  bool has_series = std::any_of(obs.groups.begin(), obs.groups.end(), [](const auto& g) { return g.series; });
  if (c.predictor.role().separating == SeparatingMeasurement::CameraTrack) {
    // The fitted models' drops at the largest condition: where their trajectories differ most.
    Outcome a = c.predictor.simulate(far, find_extension(best.id), best.params);
    Outcome b = c.predictor.simulate(far, find_extension(second.id), second.params);
    size_t n = std::min(a.trajectory.size(), b.trajectory.size());
    for (size_t k = 0; k < n; ++k) {
      double diff = std::abs(a.trajectory[k].second - b.trajectory[k].second);
      if (diff > s.largest_difference) {
        s.largest_difference = diff;
        s.at_time = a.trajectory[k].first;
      }
    }
    s.kind = has_series ? Separation::Kind::MoreDropData : Separation::Kind::DropTrajectory;
    s.condition = obs.conditions[far].label;
  } else if (c.predictor.role().separating == SeparatingMeasurement::WiderCondition) {
    s.kind = Separation::Kind::WiderCondition;
    s.condition = obs.variables.empty() ? "" : obs.variables.front();
  } else {
    s = heap_separation(c, best, second);
  }
  return s;
}

}  // namespace

DiagnosisContext describe_data(const Observations& obs, Predictor& predictor) {
  DiagnosisContext c(obs, predictor);
  c.heldout_available = obs.conditions.size() >= 3;
  if (predictor.fits_baseline()) c.case_values = {predictor.case_baseline_value()};
  c.scatter_scored = std::any_of(obs.groups.begin(), obs.groups.end(),
                                 [](const ObservationGroup& g) { return g.sigma_given && g.values.size() >= 2; });
  c.noise_df = obs.noise_df();
  // A candidate adds a parameter to the baseline's: with no more means than that, nothing is left
  // to test (one condition would come out "adequate" on zero degrees of freedom).
  std::vector<FreeParameter> fitted = predictor.parameters(nullptr);
  if (obs.groups.size() <= fitted.size() + 1) {
    std::string names;
    for (const auto& p : fitted) names += (names.empty() ? "" : ", ") + p.name;
    throw DataError(obs.path + ": " + std::to_string(obs.groups.size()) + " measured mean" +
                    (obs.groups.size() == 1 ? "" : "s") + " in " + std::to_string(obs.conditions.size()) + " condition" +
                    (obs.conditions.size() == 1 ? "" : "s") + ", and the baseline fits " + std::to_string(fitted.size()) +
                    " parameter" + (fitted.size() == 1 ? "" : "s") + (names.empty() ? "" : " (" + names + ")") +
                    ": a candidate adds one more, which leaves no degree of freedom to test anything. Measure at least " +
                    std::to_string(fitted.size() + 2) + " conditions (3 or more also let diagnose predict held-out ones)");
  }
  return c;
}

CandidateSelection select_candidates(const Observations& obs, const std::vector<std::string>& requested,
                                     bool scatter_scored) {
  CandidateSelection s;
  for (const auto& e : model_extensions()) {
    if (!requested.empty() && std::find(requested.begin(), requested.end(), e.id) == requested.end()) continue;
    std::string reason = untestable_reason(e, obs, scatter_scored);
    if (reason.empty() && e.apply) {
      s.testable.push_back(&e);
      continue;
    }
    ModelResult r;
    r.id = e.id;
    r.tested = false;
    r.untested_reason = reason;
    s.untestable.push_back(r);
  }
  for (const auto& id : requested)
    if (!find_extension(id)) throw std::runtime_error("unknown extension '" + id + "'");
  return s;
}

std::vector<LackOfFit> lack_of_fit(const Observations& obs, const ModelResult& base, int noise_df) {
  std::vector<LackOfFit> out;
  LackOfFit overall;
  overall.measure = "all";
  overall.chi2 = base.chi2;
  overall.groups = score_terms(obs);
  overall.df = std::max(1, overall.groups - base.k);
  overall.noise_df = noise_df;
  overall.p = stats::f_upper_tail(overall.chi2 / overall.df, overall.df, noise_df);
  out.push_back(overall);
  std::vector<double> base_terms = group_chi_squares(obs, base.prediction);
  for (const std::string& m : obs.measures) {
    LackOfFit l;
    l.measure = m;
    for (size_t g = 0; g < obs.groups.size(); ++g) {
      if (obs.groups[g].measure != m) continue;
      l.chi2 += base_terms[g];
      l.groups += 1 + (obs.groups[g].sigma_given && obs.groups[g].values.size() >= 2 ? 1 : 0);
    }
    l.df = l.groups;
    l.noise_df = obs.noise.at(m).df;
    l.p = stats::f_upper_tail(l.chi2 / l.df, l.df, l.noise_df);
    out.push_back(l);
  }
  return out;
}

std::vector<Trend> residual_trends(const Observations& obs, const Prediction& predicted) {
  std::vector<Trend> trends;
  for (const std::string& m : obs.measures) {
    std::vector<std::string> variables = obs.variables;
    bool series = false;
    for (const auto& g : obs.groups) series = series || (g.measure == m && g.series);
    if (series) variables.push_back("t");
    for (const std::string& v : variables) {
      std::vector<double> x, r, w;
      for (size_t g = 0; g < obs.groups.size(); ++g) {
        const auto& grp = obs.groups[g];
        if (grp.measure != m) continue;
        const auto& vars = obs.conditions[grp.condition].variables;
        if (v == "t") x.push_back(grp.t);
        else if (vars.count(v)) x.push_back(vars.at(v));
        else continue;
        r.push_back(grp.mean - predicted.mean[g]);
        // Correlated frames of a series carry (1 + rho) / (1 - rho) times less information.
        double measured = 1.0 / grp.weight() * (grp.series ? obs.noise.at(m).inflation : 1.0);
        w.push_back(1.0 / (measured + predicted.variance_of_mean(g)));
      }
      if (x.size() < 3) continue;
      Trend t = slope_of(x, r, w);
      t.measure = m;
      t.variable = v;
      trends.push_back(t);
    }
  }
  return trends;
}

namespace {

// Significant candidates, best AIC first.
std::vector<size_t> significant_by_aic(const std::vector<ModelResult>& fitted) {
  std::vector<size_t> out;
  for (size_t k = 0; k < fitted.size(); ++k)
    if (fitted[k].significant) out.push_back(k);
  std::sort(out.begin(), out.end(), [&](size_t a, size_t b) { return fitted[a].aic < fitted[b].aic; });
  return out;
}

}  // namespace

bool rival_mimics(double chi2, double aic_difference) {
  // A rival that could mimic the winner's predictions is still no rival when the data themselves
  // reject it (its Akaike weight below e^-5 of the winner's).
  return (chi2 < kSeparableChi2 && aic_difference < kAicRejected) || aic_difference < kAicClose;
}

std::vector<MimicTest> mimic_tests(DiagnosisContext& c, const ModelResult& base, const std::vector<ModelResult>& fitted) {
  std::vector<MimicTest> out;
  std::vector<size_t> significant = significant_by_aic(fitted);
  if (significant.empty()) return out;
  std::vector<char> everything(c.obs.conditions.size(), 1);
  auto mimic = [&](const ModelResult& rival, const ModelResult& target) {
    SurfaceMinimum m = c.surrogate(find_extension(rival.id)).fit(everything, &target.prediction, 3);
    MimicTest t{rival.id, target.id, m.score, rival.aic - target.aic, false};
    t.close = rival_mimics(t.chi2, t.aic_difference);
    out.push_back(t);
  };
  const ModelResult& best = fitted[significant[0]];
  // The rivals of the best in order of AIC, then the other significant pairs.
  std::vector<size_t> rivals;
  for (size_t k = 0; k < fitted.size(); ++k)
    if (k != significant[0] && fitted[k].aic < base.aic) rivals.push_back(k);
  std::sort(rivals.begin(), rivals.end(), [&](size_t a, size_t b) { return fitted[a].aic < fitted[b].aic; });
  for (size_t r : rivals) mimic(fitted[r], best);
  for (size_t a : significant)
    for (size_t b : significant)
      if (a != b && b != significant[0]) mimic(fitted[a], fitted[b]);
  return out;
}

std::vector<PairSeparation> pair_separations(const std::vector<MimicTest>& mimics) {
  std::vector<PairSeparation> pairs;
  for (const MimicTest& m : mimics) {
    auto it = std::find_if(pairs.begin(), pairs.end(), [&](const PairSeparation& p) {
      return (p.a == m.rival && p.b == m.winner) || (p.a == m.winner && p.b == m.rival);
    });
    if (it == pairs.end()) {
      pairs.push_back({m.winner, m.rival});
      pairs.back().told_apart = true;
      it = pairs.end() - 1;
    }
    (it->a == m.rival ? it->a_as_b : it->b_as_a) = m.chi2;
    if (m.close) it->told_apart = false;
  }
  return pairs;
}

std::vector<std::string> untested_rivals(const Observations& obs, const std::vector<ModelResult>& failed,
                                         const std::vector<LackOfFit>& lack) {
  std::vector<std::string> out;
  if (lack.empty() || !(lack.front().p < kDiagnosisSignificance)) return out;
  for (const ModelResult& r : failed) {
    const ModelExtension* e = find_extension(r.id);
    if (!e || r.simulation_error.empty()) continue;
    bool acts = std::any_of(obs.measures.begin(), obs.measures.end(), [&](const std::string& m) {
      return std::find(e->revealed_by.begin(), e->revealed_by.end(), m) != e->revealed_by.end();
    });
    if (acts) out.push_back(r.id);
  }
  return out;
}

namespace {

// No candidate beats the baseline. One whose evidence disagrees (the lowest AIC first) is named as
// ambiguous: the baseline has no confident claim while such evidence stands. Else the baseline is
// adequate, or the data unexplained when it misses them.
Verdict undecided_verdict(const DiagnosisContext& c, const ModelResult& base, const std::vector<ModelResult>& results,
                          const std::vector<std::string>& untested, const std::vector<LackOfFit>& lack) {
  Verdict v;
  int split = -1;
  for (size_t k = 0; k < results.size(); ++k)
    if (results[k].standing != Standing::NoBetter && results[k].standing != Standing::Beats &&
        (split < 0 || results[k].aic < results[size_t(split)].aic))
      split = int(k);
  if (split < 0) {
    // A baseline that misses the data is not adequate because nothing tested beats it.
    bool missed = !lack.empty() && lack.front().p < kDiagnosisSignificance;
    v.verdict = missed ? "unexplained" : "adequate";
    return v;
  }
  const ModelResult& named = results[size_t(split)];
  v.verdict = "ambiguous";
  v.winner = split;
  v.cause.push_back(named.id);
  v.cause.insert(v.cause.end(), untested.begin(), untested.end());
  if (named.standing == Standing::HeldOutAgainst) {
    // In-sample it wins, held out it does not: more conditions (or a wider range) would decide.
    v.separation.kind = Separation::Kind::WiderCondition;
    v.separation.condition = c.obs.variables.empty() ? "" : c.obs.variables.front();
    return v;
  }
  // The F statistic grows about in proportion to the replicates: how many times as many put it
  // at the 1 % level.
  v.separation.kind = Separation::Kind::MoreReplicates;
  int dk = std::max(1, named.k - base.k);
  double needed = stats::f_critical(kDiagnosisSignificance, dk, c.noise_df);
  v.separation.replicate_factor = named.f > 0 ? std::max(1.0, needed / named.f) : 0;
  return v;
}

}  // namespace

Verdict decide_verdict(DiagnosisContext& c, const ModelResult& base, const std::vector<ModelResult>& results,
                       const std::vector<MimicTest>& mimics, const std::vector<std::string>& untested,
                       const std::vector<LackOfFit>& lack) {
  Verdict v;
  std::vector<size_t> winners = significant_by_aic(results);
  if (winners.empty()) return undecided_verdict(c, base, results, untested, lack);
  v.winner = int(winners[0]);
  const ModelResult& best = results[winners[0]];
  v.cause.push_back(best.id);
  // A rival that improves on the baseline at all and mimics the winner leaves the cause undecided.
  for (const MimicTest& m : mimics) {
    if (m.winner != best.id) continue;
    if (v.separation_chi2 < 0 || m.chi2 < v.separation_chi2) v.separation_chi2 = m.chi2;
    if (m.close) v.cause.push_back(m.rival);
    v.mimics.push_back(m);
  }
  // So does a candidate that might explain the data but could not be tested.
  v.cause.insert(v.cause.end(), untested.begin(), untested.end());
  if (v.cause.size() == 1) {
    v.verdict = "effect";
    return v;
  }
  v.verdict = "ambiguous";
  if (v.cause.size() == 1 + untested.size()) {
    v.separation.kind = Separation::Kind::Untested;
    v.separation.measure = untested.front();
    return v;
  }
  const ModelResult& second =
      *std::find_if(results.begin(), results.end(), [&](const ModelResult& r) { return r.id == v.cause[1]; });
  v.separation = separation_of(c, best, second);
  return v;
}

Confidence verdict_confidence(const ModelResult& base, const std::vector<ModelResult>& fitted, const Verdict& v,
                              const std::vector<std::string>& untested) {
  Confidence out;
  double best = base.aic;
  for (const ModelResult& r : fitted) best = std::min(best, r.aic);
  double total = 0;
  auto add = [&](const std::string& id, double aic) {
    double w = std::exp(-0.5 * (aic - best));
    out.weights.push_back({id, w});
    total += w;
  };
  add("baseline", base.aic);
  for (const ModelResult& r : fitted) add(r.id, r.aic);
  for (const std::string& id : untested) add(id, best);
  for (auto& [id, w] : out.weights) w /= total;
  std::string named = v.cause.empty() ? "baseline" : v.cause.front();
  for (const auto& [id, w] : out.weights)
    if (id == named) out.named = w;
  return out;
}

HeldOutGain heldout_gain(const DiagnosisContext& c, const ModelResult& base, const Verdict& v,
                         const std::vector<ModelResult>& fitted) {
  HeldOutGain g;
  g.baseline = base.heldout_sds;
  g.extended = v.winner >= 0 ? fitted[size_t(v.winner)].heldout_sds : base.heldout_sds;
  if (c.heldout_available && base.heldout_sds > 0) g.percent = 100.0 * (1.0 - g.extended / base.heldout_sds);
  return g;
}

}  // namespace repose
