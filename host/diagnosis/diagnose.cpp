#include "diagnosis/diagnose.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "stats/fdist.h"

namespace repose {

namespace {

constexpr double kSignificance = 0.01;  // an extension must beat the baseline at 1 %
constexpr double kSeparable = 9.0;      // chi^2 by which the runner-up must miss the winner (3 sigma)
constexpr double kAicClose = 2.0;       // Burnham & Anderson: models within 2 have equal support

std::string num(double v, int digits = 4) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

// A length in mm, anything else in its own unit.
std::string in_unit(double v, const std::string& unit) {
  if (unit == "m") return num(v * 1000, 3) + " mm";
  return num(v, 3) + (unit == "1" ? "" : " " + unit);
}

double two_sided_normal_p(double z) { return std::erfc(std::abs(z) / std::sqrt(2.0)); }

const char* unit_of(const std::string& measure) {
  for (const auto& m : known_measures())
    if (measure == m.name) return m.unit;
  return "";
}

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

std::vector<Trend> residual_trends(const Observations& obs, const std::vector<double>& predicted) {
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
        r.push_back(grp.mean - predicted[g]);
        // Correlated frames of a series carry (1 + rho) / (1 - rho) times less information.
        w.push_back(grp.weight() / (grp.series ? obs.noise.at(m).inflation : 1.0));
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

class Steps {
 public:
  Steps(int total, bool enabled) : total_(total), enabled_(enabled), start_(std::chrono::steady_clock::now()) {}
  void next(const std::string& what) {
    ++done_;
    if (!enabled_) return;
    double s = seconds();
    double eta = done_ > 1 ? s / (done_ - 1) * (total_ - done_ + 1) : 0;
    std::fprintf(stderr, "diagnose: fit %d/%d %-44s %6.1f s elapsed, ETA %.0f s\n", done_, total_, what.c_str(), s,
                 eta);
  }
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  int total_, done_ = 0;
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

Diagnosis diagnose(const Observations& obs, const DiagnoseOptions& options) {
  Predictor predictor(obs, options.given, options.fit_baseline, options.threads, options.simulated_replicates);
  Diagnosis d;
  size_t nc = obs.conditions.size();
  std::vector<char> all(nc, 1);
  d.heldout_available = nc >= 3;
  d.primary_measure = obs.measures.front();
  for (const auto& g : obs.groups)
    if (!g.series) { d.primary_measure = g.measure; break; }
  d.primary_unit = unit_of(d.primary_measure);
  d.scatter_scored = std::any_of(obs.groups.begin(), obs.groups.end(),
                                 [](const ObservationGroup& g) { return g.sigma_given && g.values.size() >= 2; });
  int noise_df = obs.noise_df();

  // Which candidates the data can speak to.
  std::vector<const ModelExtension*> tested;
  for (const auto& e : model_extensions()) {
    if (!options.candidates.empty() &&
        std::find(options.candidates.begin(), options.candidates.end(), e.id) == options.candidates.end())
      continue;
    ModelResult r;
    r.id = e.id;
    bool revealed = false;
    for (const auto& m : obs.measures)
      revealed = revealed || std::find(e.revealed_by.begin(), e.revealed_by.end(), m) != e.revealed_by.end();
    if (!e.apply) {
      r.tested = false;
      r.untested_reason = e.pending_reason;
    } else if (!revealed) {
      r.tested = false;
      std::string shows;
      for (const auto& m : e.revealed_by) shows += (shows.empty() ? "" : ", ") + m;
      r.untested_reason = "none of the measured quantities responds to it (it shows in " + shows + ")";
    } else if (e.needs_sigma && !d.scatter_scored) {
      r.tested = false;
      r.untested_reason = "its signature is the replicate scatter, which without a sigma column (the measurement "
                          "error) is taken as the noise: give sigma to test it";
    } else {
      tested.push_back(&e);
    }
    if (!r.tested) d.candidates.push_back(r);
  }
  for (const auto& id : options.candidates)
    if (!find_extension(id)) throw std::runtime_error("unknown extension '" + id + "'");

  Steps steps(int((1 + tested.size()) * (1 + (d.heldout_available ? nc : 0)) + 1), options.progress);

  auto fit_with_heldout = [&](const ModelExtension* ext) {
    ModelResult r;
    r.id = ext ? ext->id : "baseline";
    r.parameters = predictor.parameters(ext);
    r.k = int(r.parameters.size());
    steps.next(r.id + ", all conditions");
    // Extensions start from the baseline's fitted values (their own parameters scanned).
    std::vector<double> start;
    if (ext) start = d.baseline.params;
    ModelFit full = fit_model(predictor, ext, all, start);
    r.params = full.params;
    r.prediction = full.predicted;
    r.predicted = full.predicted.mean;
    if (d.scatter_scored)
      for (size_t g = 0; g < obs.groups.size(); ++g)
        r.predicted_sd.push_back(std::sqrt(obs.groups[g].sd * obs.groups[g].sd + full.predicted.var[g]));
    r.chi2 = full.chi2;
    r.aic = r.chi2 + 2.0 * r.k;
    if (d.heldout_available) {
      Prediction held = full.predicted;
      for (size_t c = 0; c < nc; ++c) {
        steps.next(r.id + ", without " + obs.conditions[c].label);
        std::vector<char> use(nc, 1), only(nc, 0);
        use[c] = 0;
        only[c] = 1;
        ModelFit loo = fit_model(predictor, ext, use, full.params, 0.05, 30);
        Prediction pred = r.k ? predictor.predict(ext, loo.params, only) : full.predicted;
        held.replicates = pred.replicates;
        for (size_t g = 0; g < obs.groups.size(); ++g)
          if (obs.groups[g].condition == c) {
            held.mean[g] = pred.mean[g];
            held.var[g] = pred.var[g];
          }
      }
      r.heldout = held.mean;
      // Held-out error of the primary measure: RMS error of the mean or, when the file gives sigma
      // (the scatter is data too), the 2-Wasserstein distance between the measured and predicted
      // normal distributions of one value, sqrt((mean error)^2 + (SD error)^2), in the same unit.
      double se = 0, sz = 0;
      int ne = 0;
      std::vector<double> held_terms = group_chi_squares(obs, held);
      for (size_t g = 0; g < obs.groups.size(); ++g) {
        const ObservationGroup& grp = obs.groups[g];
        double e = grp.mean - held.mean[g];
        sz += held_terms[g];
        if (grp.measure != d.primary_measure) continue;
        double e2 = e * e;
        if (grp.sigma_given && grp.values.size() >= 2) {
          double sd_error = std::sqrt(grp.s2) - std::sqrt(grp.sd * grp.sd + held.var[g]);
          e2 += sd_error * sd_error;
        }
        se += e2;
        ++ne;
      }
      r.heldout_rms = std::sqrt(se / std::max(1, ne));
      r.heldout_z = std::sqrt(sz / score_terms(obs));
    }
    return r;
  };

  // 1. The baseline and what is wrong with it.
  d.baseline = fit_with_heldout(nullptr);
  const ModelResult& base = d.baseline;
  {
    std::string fitted;
    for (size_t k = 0; k < base.params.size(); ++k)
      fitted += (k ? ", " : "") + base.parameters[k].name + " = " + num(base.params[k]);
    d.statements.push_back("Baseline (" + predictor.diagnosed().baseline_model + "): " +
                           (fitted.empty() ? std::string("parameters as given") : "fitted " + fitted) +
                           "; chi^2 = " + num(base.chi2) + " over " + std::to_string(obs.groups.size()) +
                           " measured means, weighed by their replicate scatter" +
                           (d.scatter_scored ? std::string(", and their replicate variances against the given "
                                                           "sigma (the scatter is data too)")
                                             : std::string()) +
                           ".");
  }
  for (const auto& [m, n] : obs.noise)
    if (n.inflation > 1.2)
      d.statements.push_back("The " + m + " series' noise is correlated from frame to frame (lag-1 correlation " +
                             num(n.lag1, 2) + " of the replicates' deviations along t): the residuals are whitened as AR(1) "
                             "in the score, and the trend tests count " + num(n.inflation, 3) +
                             " frames as one.");
  LackOfFit overall;
  overall.measure = "all";
  overall.chi2 = base.chi2;
  overall.groups = score_terms(obs);
  overall.df = std::max(1, overall.groups - base.k);
  overall.noise_df = noise_df;
  overall.p = stats::f_upper_tail(overall.chi2 / overall.df, overall.df, noise_df);
  d.lack_of_fit.push_back(overall);
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
    d.lack_of_fit.push_back(l);
  }
  if (overall.p < kSignificance)
    d.statements.push_back("Lack of fit: the baseline misses the measured means by more than their replicate scatter "
                           "allows (chi^2/df = " + num(overall.chi2 / overall.df, 3) + ", F test p = " +
                           num(overall.p, 2) + ").");
  else
    d.statements.push_back("No lack of fit: the baseline agrees with the measured means within their replicate "
                           "scatter (chi^2/df = " + num(overall.chi2 / overall.df, 3) + ", p = " + num(overall.p, 2) + ").");
  d.trends = residual_trends(obs, base.predicted);
  for (const Trend& t : d.trends) {
    std::string unit = unit_of(t.measure);
    std::string per = t.variable == "t" ? "s" : t.variable.substr(t.variable.rfind('.') + 1);
    if (t.p < kSignificance)
      d.statements.push_back("Residuals of " + t.measure + " (measured - simulated) " +
                             (t.slope > 0 ? "rise" : "fall") + " with " + (t.variable == "t" ? "time in the series" : t.variable) +
                             ": slope " + num(t.slope, 3) + " " + unit + " per " + per + " (z = " + num(t.z, 3) +
                             ", p = " + num(t.p, 2) + "): the baseline " +
                             (t.slope > 0 ? "under" : "over") + "-predicts at large " +
                             (t.variable == "t" ? "t" : per) + ".");
    else
      d.statements.push_back("No significant trend of " + t.measure + " residuals with " + t.variable + " (p = " +
                             num(t.p, 2) + ").");
  }

  // 2. Every candidate extension, fitted and compared with the baseline.
  std::vector<ModelResult> results;
  for (const ModelExtension* ext : tested) {
    ModelResult r;
    try {
      r = fit_with_heldout(ext);
    } catch (const std::runtime_error& e) {
      // A candidate whose experiment cannot be simulated to the end (e.g. a heap that never
      // settles under it) is reported untested with the reason; the others still count.
      ModelResult failed;
      failed.id = ext->id;
      failed.tested = false;
      failed.untested_reason = std::string("its simulation failed: ") + e.what();
      d.candidates.push_back(failed);
      d.statements.push_back(ext->id + ": not tested, its simulation failed (" + e.what() + ").");
      continue;
    }
    int dk = std::max(1, r.k - base.k);
    r.f = std::max(0.0, base.chi2 - r.chi2) / dk;
    r.p = stats::f_upper_tail(r.f, dk, noise_df);
    r.significant = r.p < kSignificance && (!d.heldout_available || r.heldout_z < base.heldout_z);
    std::string fitted;
    for (size_t k = 0; k < r.params.size(); ++k)
      fitted += (k ? ", " : "") + r.parameters[k].name + " = " + num(r.params[k]);
    d.statements.push_back(r.id + ": " + fitted + "; chi^2 " + num(base.chi2) + " -> " + num(r.chi2) +
                           " (F = " + num(r.f, 3) + ", p = " + num(r.p, 2) + "), AIC " + num(base.aic) + " -> " +
                           num(r.aic) +
                           (d.heldout_available ? ", held-out error " + in_unit(r.heldout_rms, d.primary_unit) +
                                                      " vs " + in_unit(base.heldout_rms, d.primary_unit) +
                                                      " (baseline)"
                                                : std::string()) +
                           (r.significant ? ": beats the baseline." : ": no better than the baseline."));
    Predictor::FillRecord fill = predictor.fills(r.id);
    if (fill.fallback > 0)
      d.statements.push_back(r.id + ": " + std::to_string(fill.fallback) + " of its " + std::to_string(fill.heaps) +
                             " heaps did not fit the case's fill box by random insertion and were filled largest "
                             "grain first" +
                             (fill.most_raised > 0 ? " in the box raised by up to " + num(100 * fill.most_raised, 3) +
                                                         " % of its height"
                                                   : std::string()) +
                             ".");
    results.push_back(r);
  }

  // 3. The verdict.
  std::vector<size_t> winners;
  for (size_t k = 0; k < results.size(); ++k)
    if (results[k].significant) winners.push_back(k);
  std::sort(winners.begin(), winners.end(), [&](size_t a, size_t b) { return results[a].aic < results[b].aic; });
  if (winners.empty()) {
    d.verdict = "adequate";
    d.statements.push_back("Verdict: the baseline is adequate; no candidate extension explains the data better "
                           "(each fails the F test at 1 % or the held-out comparison).");
    if (overall.p < kSignificance) {
      std::string untested;
      for (const auto& c : d.candidates)
        if (!c.tested) untested += (untested.empty() ? "" : ", ") + c.id;
      d.statements.push_back("But the baseline does miss the data (lack of fit above): the cause lies outside the "
                             "candidates tested" +
                             (untested.empty() ? std::string(".") : " (not testable with these measures: " + untested + ")."));
    }
  } else {
    const ModelResult& best = results[winners[0]];
    d.cause.push_back(best.id);
    std::vector<char> everything(nc, 1);
    // Rivals: every other candidate that improves on the baseline at all (lower AIC), significant
    // or not: one that fits nearly as well as the winner leaves the cause undecided.
    std::vector<size_t> rivals;
    for (size_t k = 0; k < results.size(); ++k)
      if (k != winners[0] && results[k].aic < base.aic) rivals.push_back(k);
    std::sort(rivals.begin(), rivals.end(), [&](size_t a, size_t b) { return results[a].aic < results[b].aic; });
    for (size_t w : rivals) {
      const ModelResult& other = results[w];
      steps.next("can " + other.id + " mimic " + best.id + "?");
      ModelFit mimic = fit_model(predictor, find_extension(other.id), everything, other.params, 0.08, 50, &best.prediction);
      bool close = mimic.chi2 < kSeparable || other.aic - best.aic < kAicClose;
      if (d.separation_chi2 < 0 || mimic.chi2 < d.separation_chi2) d.separation_chi2 = mimic.chi2;
      if (close) d.cause.push_back(other.id);
      d.statements.push_back(other.id + " refitted to " + best.id + "'s predictions misses them by chi^2 = " +
                             num(mimic.chi2, 3) + " (separable at 3 sigma above " + num(kSeparable, 2) +
                             "); AIC difference " + num(other.aic - best.aic, 3) + ".");
    }
    if (d.cause.size() == 1) {
      d.verdict = "effect";
      std::string fitted;
      for (size_t k = 0; k < best.params.size(); ++k)
        fitted += (k ? ", " : "") + best.parameters[k].name + " = " + num(best.params[k]);
      d.statements.push_back("Verdict: effect. The cause is " + best.id + " (" + fitted + ").");
    } else {
      d.verdict = "ambiguous";
      std::string names;
      for (const auto& c : d.cause) names += (names.empty() ? "" : " and ") + c;
      // Which measurement tells them apart: the fitted models' drops at the largest condition.
      size_t far = nc - 1;
      const ModelResult& second = *std::find_if(results.begin(), results.end(),
                                                [&](const ModelResult& r) { return r.id == d.cause[1]; });
      bool has_series = std::any_of(obs.groups.begin(), obs.groups.end(), [](const auto& g) { return g.series; });
      if (predictor.experiment() == "drop") {
        Outcome a = predictor.simulate(far, find_extension(best.id), best.params);
        Outcome b = predictor.simulate(far, find_extension(second.id), second.params);
        double worst = 0, at = 0;
        size_t n = std::min(a.trajectory.size(), b.trajectory.size());
        for (size_t k = 0; k < n; ++k) {
          double diff = std::abs(a.trajectory[k].second - b.trajectory[k].second);
          if (diff > worst) { worst = diff; at = a.trajectory[k].first; }
        }
        d.separating_measurement =
            has_series ? "more replicates or a wider range of conditions (the trajectories already measured differ "
                         "too little between the two)"
                       : "the trajectory z(t) of the drop (measure 'height' with a t column, from the camera): the two "
                         "fitted models differ there by up to " + num(worst * 1000, 3) + " mm at t = " + num(at, 3) +
                         " s in condition " + obs.conditions[far].label + ", while their rebound heights agree";
      } else if (predictor.experiment() != "repose") {
        d.separating_measurement = "more replicates, or a wider range of the condition (" +
                                   (obs.variables.empty() ? std::string("none varies yet") : obs.variables.front()) +
                                   ")";
      } else {
        bool has_bed = std::find(obs.measures.begin(), obs.measures.end(), "bed_height") != obs.measures.end();
        d.separating_measurement =
            has_bed ? "more replicate heaps, or a second rig that loads the grains differently (a flow or a shear "
                      "test): the angle and the bed height move alike under both"
                    : "the bed height before the lift (measure 'bed_height'): packing separates a size spread from "
                      "rolling resistance, which the angle alone confounds";
      }
      d.statements.push_back("Verdict: ambiguous between " + names + ": the data cannot tell them apart. " +
                             "To separate them, measure " + d.separating_measurement + ".");
    }
    d.heldout_error_extended = best.heldout_rms;
  }
  d.heldout_error_baseline = base.heldout_rms;
  if (winners.empty()) d.heldout_error_extended = base.heldout_rms;
  if (d.heldout_available && base.heldout_rms > 0)
    d.gain_percent = 100.0 * (1.0 - d.heldout_error_extended / base.heldout_rms);
  if (d.heldout_available && !winners.empty())
    d.statements.push_back("Gain: leaving each condition out in turn, the " + d.cause[0] + " model predicts " +
                           d.primary_measure + (d.scatter_scored ? " (mean and replicate SD)" : "") + " to " +
                           in_unit(d.heldout_error_extended, d.primary_unit) + " (RMS), the baseline to " + in_unit(d.heldout_error_baseline, d.primary_unit) + ": " +
                           num(d.gain_percent, 3) + " % less error.");
  for (auto& r : results) d.candidates.push_back(r);
  d.simulations = predictor.simulations();
  d.seconds = steps.seconds();
  return d;
}

}  // namespace repose
