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

// The held-out prediction of every group: each condition predicted by a fit to the others.
Prediction hold_out_each_condition(DiagnosisContext& c, const ModelExtension* ext, const ModelResult& r,
                                   const Prediction& full) {
  const Observations& obs = c.obs;
  size_t nc = obs.conditions.size();
  Prediction held = full;
  for (size_t k = 0; k < nc; ++k) {
    if (c.progress) c.progress->next(r.id + ", without " + obs.conditions[k].label);
    std::vector<char> use(nc, 1), only(nc, 0);
    use[k] = 0;
    only[k] = 1;
    ModelFit loo = fit_model(c.predictor, ext, use, r.params, 0.05, 30);
    Prediction pred = r.k ? c.predictor.predict(ext, loo.params, only) : full;
    held.replicates = pred.replicates;
    for (size_t g = 0; g < obs.groups.size(); ++g)
      if (obs.groups[g].condition == k) {
        held.mean[g] = pred.mean[g];
        held.var[g] = pred.var[g];
      }
  }
  return held;
}

// Held-out error of the primary measure: RMS error of the mean or, when the file gives sigma (the
// scatter is data too), the 2-Wasserstein distance between the measured and predicted normal
// distributions of one value, sqrt((mean error)^2 + (SD error)^2), in the same unit; and the root
// mean square standardised error over every group.
void score_held_out(const DiagnosisContext& c, const Prediction& held, ModelResult& r) {
  const Observations& obs = c.obs;
  double se = 0, sz = 0;
  int ne = 0;
  std::vector<double> held_terms = group_chi_squares(obs, held);
  for (size_t g = 0; g < obs.groups.size(); ++g) {
    const ObservationGroup& grp = obs.groups[g];
    double e = grp.mean - held.mean[g];
    sz += held_terms[g];
    if (grp.measure != c.primary_measure) continue;
    double e2 = e * e;
    if (grp.sigma_given && grp.values.size() >= 2) {
      double sd_error = std::sqrt(grp.s2) - std::sqrt(grp.sd * grp.sd + held.var[g]);
      e2 += sd_error * sd_error;
    }
    se += e2;
    ++ne;
  }
  r.heldout = held.mean;
  r.heldout_rms = std::sqrt(se / std::max(1, ne));
  r.heldout_z = std::sqrt(sz / score_terms(obs));
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
  int reps = c.predictor.simulated_replicates();
  for (const std::string& m : heap_measure_names()) {
    double difference = 0, variance = 0;
    for (size_t k = 0; k < obs.conditions.size(); ++k) {
      double mean[2] = {0, 0}, square[2] = {0, 0};
      const ModelResult* models[2] = {&best, &second};
      for (int i = 0; i < 2; ++i)
        for (int r = 0; r < reps; ++r) {
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

FitProgress::FitProgress(int total, bool enabled)
    : total_(total), enabled_(enabled), start_(std::chrono::steady_clock::now()) {}

void FitProgress::next(const std::string& what) {
  ++done_;
  if (!enabled_) return;
  double s = seconds();
  double eta = done_ > 1 ? s / (done_ - 1) * (total_ - done_ + 1) : 0;
  std::fprintf(stderr, "diagnose: fit %d/%d %-44s %6.1f s elapsed, ETA %.0f s\n", done_, total_, what.c_str(), s, eta);
}

double FitProgress::seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

DiagnosisContext describe_data(const Observations& obs, Predictor& predictor) {
  DiagnosisContext c(obs, predictor);
  c.heldout_available = obs.conditions.size() >= 3;
  c.primary_measure = obs.measures.front();
  for (const auto& g : obs.groups)
    if (!g.series) {
      c.primary_measure = g.measure;
      break;
    }
  c.primary_unit = unit_of(c.primary_measure);
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

ModelResult fit_and_hold_out(DiagnosisContext& c, const ModelExtension* ext, const ModelResult* baseline) {
  const Observations& obs = c.obs;
  ModelResult r;
  r.id = ext ? ext->id : "baseline";
  r.parameters = c.predictor.parameters(ext);
  r.k = int(r.parameters.size());
  if (c.progress) c.progress->next(r.id + ", all conditions");
  std::vector<double> start;
  if (ext && baseline) start = baseline->params;
  std::vector<char> all(obs.conditions.size(), 1);
  ModelFit full = fit_model(c.predictor, ext, all, start);
  r.params = full.params;
  r.fit_chi2 = full.chi2;
  r.prediction = full.predicted;
  r.chi2 = full.chi2;
  if (full.predicted.replicates > 1) {  // stochastic: scored on fresh replicates
    r.prediction = c.predictor.predict(ext, r.params, all, c.predictor.simulated_replicates(),
                                       c.predictor.confirmation_replicates());
    r.chi2 = chi_square(obs, r.prediction, all);
  }
  r.predicted = r.prediction.mean;
  if (c.scatter_scored)
    for (size_t g = 0; g < obs.groups.size(); ++g)
      r.predicted_sd.push_back(std::sqrt(obs.groups[g].sd * obs.groups[g].sd + r.prediction.var[g]));
  r.aic = r.chi2 + 2.0 * r.k;
  if (c.heldout_available) score_held_out(c, hold_out_each_condition(c, ext, r, full.predicted), r);
  return r;
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

void compare_with_baseline(const Observations& obs, ModelResult& r, const ModelResult& base, int noise_df,
                           bool heldout_available) {
  ShrunkChange change = shrink_change(obs, base.prediction, r.prediction);
  r.shrinkage = change.shrinkage;
  r.change_d2 = change.d2;
  // Fresh replicates and shrinking only take away: a candidate scores no better than on the
  // replicates it was fitted to, on fresh ones, or with its change shrunk, whichever is worst.
  r.chi2 = std::max(r.chi2, r.fit_chi2);
  if (change.shrinkage < 1)
    r.chi2 = std::max(r.chi2, chi_square(obs, change.prediction, std::vector<char>(obs.conditions.size(), 1)));
  r.aic = r.chi2 + 2.0 * r.k;
  int dk = std::max(1, r.k - base.k);
  r.f = std::max(0.0, base.chi2 - r.chi2) / dk;
  r.p = stats::f_upper_tail(r.f, dk, noise_df);
  r.significant = r.p < kDiagnosisSignificance && (!heldout_available || r.heldout_z < base.heldout_z);
}

CandidateFits fit_candidates(DiagnosisContext& c, const std::vector<const ModelExtension*>& testable,
                             const ModelResult& baseline) {
  CandidateFits out;
  for (const ModelExtension* ext : testable) {
    out.tried.push_back(ext->id);
    try {
      ModelResult r = fit_and_hold_out(c, ext, &baseline);
      compare_with_baseline(c.obs, r, baseline, c.noise_df, c.heldout_available);
      Predictor::FillRecord fill = c.predictor.fills(r.id);
      r.heaps = fill.heaps;
      r.refilled = fill.fallback;
      r.fill_raised = fill.most_raised;
      out.fitted.push_back(r);
    } catch (const std::runtime_error& e) {
      ModelResult failed;
      failed.id = ext->id;
      failed.tested = false;
      failed.simulation_error = e.what();
      failed.untested_reason = std::string("its simulation failed: ") + e.what();
      out.failed.push_back(failed);
    }
  }
  return out;
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

std::vector<MimicTest> mimic_tests(DiagnosisContext& c, const ModelResult& base, const std::vector<ModelResult>& fitted) {
  std::vector<MimicTest> out;
  std::vector<size_t> significant = significant_by_aic(fitted);
  if (significant.empty()) return out;
  std::vector<char> everything(c.obs.conditions.size(), 1);
  auto mimic = [&](const ModelResult& rival, const ModelResult& target) {
    if (c.progress) c.progress->next("can " + rival.id + " mimic " + target.id + "?");
    ModelFit m = fit_model(c.predictor, find_extension(rival.id), everything, rival.params, 0.08, 50, &target.prediction);
    MimicTest t{rival.id, target.id, m.chi2, rival.aic - target.aic, false};
    t.close = t.chi2 < kSeparableChi2 || t.aic_difference < kAicClose;
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
      it = pairs.end() - 1;
    }
    (it->a == m.rival ? it->a_as_b : it->b_as_a) = m.chi2;
  }
  for (PairSeparation& p : pairs)
    p.told_apart = (p.a_as_b < 0 || p.a_as_b >= kSeparableChi2) && (p.b_as_a < 0 || p.b_as_a >= kSeparableChi2);
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

Verdict decide_verdict(DiagnosisContext& c, const ModelResult& base, const std::vector<ModelResult>& results,
                       const std::vector<MimicTest>& mimics, const std::vector<std::string>& untested,
                       const std::vector<LackOfFit>& lack) {
  Verdict v;
  std::vector<size_t> winners = significant_by_aic(results);
  if (winners.empty()) {
    // A baseline that misses the data is not adequate because nothing tested beats it.
    bool missed = !lack.empty() && lack.front().p < kDiagnosisSignificance;
    v.verdict = missed ? "unexplained" : "adequate";
    return v;
  }
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
  g.baseline = base.heldout_rms;
  g.extended = v.winner >= 0 ? fitted[size_t(v.winner)].heldout_rms : base.heldout_rms;
  if (c.heldout_available && base.heldout_rms > 0) g.percent = 100.0 * (1.0 - g.extended / base.heldout_rms);
  return g;
}

}  // namespace repose
