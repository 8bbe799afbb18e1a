// The fitting stages of `repose diagnose` (diagnose_stages.h): each model fitted on its surrogate
// (surrogate.h), held out condition by condition, confirmed on fresh replicates, and compared with
// the baseline; the progress of the simulations they cost.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "diagnosis/diagnose_stages.h"
#include "stats/fdist.h"

namespace repose {

namespace {

// Points a fit may add where its minimum lies: a smooth model's cost a drop each, a chaotic one's
// surface is noise-limited after a few.
int refine_points(const ModelSurrogate& s) { return s.chaotic() ? 4 : 8; }
constexpr int kValleyPasses = 3;       // passes along an extension's valley (surrogate.h)
constexpr double kOnBound = 0.005;     // of a parameter's range: a fit this near an end is on it
constexpr double kBentParameter = 0.25;  // of its range: how far a strained baseline moved a parameter

std::string duration(double s) {
  char buf[32];
  if (s < 120) std::snprintf(buf, sizeof buf, "%.0f s", s);
  else std::snprintf(buf, sizeof buf, "%.1f min", s / 60);
  return buf;
}

// The extension's design starts with the baseline's fitted values, the extension at the low end
// of its range (nearly off).
std::vector<double> design_start(const ModelSurrogate& s, const ModelResult* baseline) {
  if (!s.extension() || !baseline || baseline->params.empty()) return {};
  std::vector<double> u(s.parameters().size(), 0.0);
  for (size_t k = 0; k < baseline->params.size(); ++k) u[k] = s.parameters()[k].to_unit(baseline->params[k]);
  return u;
}

// Each condition predicted by a fit on the surface to the others: simulated there; for a chaotic
// model then read from the surface through that point (it pools the neighbouring points' fills: a
// point's own few fills are noisier), as for a candidate dropped early.
Prediction held_out(DiagnosisContext& c, ModelSurrogate& s, bool from_surface, const SurfaceMinimum& full) {
  const Observations& obs = c.obs;
  Prediction held = full.prediction;
  held.mean_var.assign(obs.groups.size(), 0.0);
  for (size_t g = 0; g < obs.groups.size(); ++g) held.mean_var[g] = full.prediction.variance_of_mean(g);
  for (size_t k = 0; k < obs.conditions.size(); ++k) {
    std::vector<char> use(obs.conditions.size(), 1);
    use[k] = 0;
    SurfaceMinimum m = from_surface ? s.minimise(use) : s.fit(use, nullptr, 2, full.u);
    Prediction p = from_surface ? m.prediction : s.simulate(m.u);
    if (!from_surface && s.chaotic()) p = s.surface(m.u);
    for (size_t g = 0; g < obs.groups.size(); ++g)
      if (obs.groups[g].condition == k) {
        held.mean[g] = p.mean[g];
        held.var[g] = p.var[g];
        held.mean_var[g] = p.variance_of_mean(g);
      }
  }
  return held;
}

// A measure's replicate scatter: the pooled sample variance of its groups (with a given sigma the
// scatter is data, not sigma), else its noise.
double replicate_scatter(const Observations& obs, const std::string& measure) {
  double ss = 0;
  int df = 0;
  for (const auto& g : obs.groups)
    if (g.measure == measure && g.values.size() >= 2) {
      ss += g.s2 * double(g.values.size() - 1);
      df += int(g.values.size()) - 1;
    }
  double sd = obs.noise.at(measure).sd;
  return df > 0 && ss > 0 ? ss / df : sd * sd;
}

// Every measure's held-out error (MeasureError) and their root mean square in standard errors.
void score_held_out(const Observations& obs, const Prediction& held, ModelResult& r) {
  r.heldout = held.mean;
  r.heldout_by_measure.clear();
  double total = 0;
  for (const std::string& m : obs.measures) {
    double scatter = std::max(replicate_scatter(obs, m), 1e-300), e2 = 0, z2 = 0;
    int count = 0;
    for (size_t g = 0; g < obs.groups.size(); ++g) {
      const ObservationGroup& grp = obs.groups[g];
      if (grp.measure != m) continue;
      double e = grp.mean - held.mean[g], sq = e * e;
      if (grp.sigma_given && grp.values.size() >= 2) {
        double sd_error = std::sqrt(grp.s2) - std::sqrt(grp.sd * grp.sd + held.var[g]);
        sq += sd_error * sd_error;
      }
      e2 += sq;
      z2 += sq / (scatter / double(grp.values.size()));
      ++count;
    }
    MeasureError me{m, std::sqrt(e2 / std::max(1, count)), std::sqrt(z2 / std::max(1, count))};
    total += me.sds * me.sds;
    r.heldout_by_measure.push_back(me);
  }
  r.heldout_sds = std::sqrt(total / double(std::max<size_t>(1, obs.measures.size())));
}

// Its best score on the design cannot reach even the modest F test against the baseline.
bool clearly_worse(const DiagnosisContext& c, double score, const ModelResult& base, int k) {
  int dk = std::max(1, k - base.k);
  return stats::f_upper_tail(std::max(0.0, base.chi2 - score) / dk, dk, c.noise_df) >= kModestSignificance;
}

}  // namespace

SimulationProgress::SimulationProgress(const Predictor& predictor, size_t planned, bool enabled)
    : predictor_(predictor), planned_(planned), enabled_(enabled), start_(std::chrono::steady_clock::now()) {}

void SimulationProgress::update(const std::string& what) {
  if (!enabled_) return;
  double s = seconds();
  size_t done = predictor_.simulations();
  if (done == 0) return;
  double eta = s / double(done) * double(planned_ > done ? planned_ - done : 0);
  if (!estimated_) {
    estimated_ = true;
    last_ = s;
    std::fprintf(stderr, "diagnose: the first %zu simulations took %s: about %s for the %zu planned\n", done,
                 duration(s).c_str(), duration(s + eta).c_str(), planned_);
    return;
  }
  if (s - last_ < 5) return;
  last_ = s;
  std::fprintf(stderr, "diagnose: %zu/%zu simulations (%s), %s elapsed, ETA %s\n", done, planned_, what.c_str(),
               duration(s).c_str(), done < planned_ ? duration(eta).c_str() : "a little more");
}

double SimulationProgress::seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

ModelSurrogate& DiagnosisContext::surrogate(const ModelExtension* extension) {
  std::string id = extension ? extension->id : "baseline";
  auto it = surrogates.find(id);
  if (it != surrogates.end()) return *it->second;
  auto made = std::make_unique<ModelSurrogate>(predictor, extension, [this](const std::string& what) {
    if (progress) progress->update(what);
  });
  return *surrogates.emplace(id, std::move(made)).first->second;
}

size_t planned_simulations(DiagnosisContext& c, const std::vector<const ModelExtension*>& testable) {
  size_t conditions = c.obs.conditions.size(), total = 0;
  std::vector<const ModelExtension*> models = {nullptr};
  models.insert(models.end(), testable.begin(), testable.end());
  for (const ModelExtension* e : models) {
    ModelSurrogate& s = c.surrogate(e);
    total += size_t(ModelSurrogate::planned_points(s.parameters().size(), conditions, s.chaotic())) * conditions *
             size_t(s.replicates_per_point());
    if (s.stochastic()) total += conditions * size_t(c.predictor.confirmation_replicates());
  }
  return total;
}

ModelResult fit_and_hold_out(DiagnosisContext& c, const ModelExtension* ext, const ModelResult* baseline) {
  const Observations& obs = c.obs;
  ModelSurrogate& s = c.surrogate(ext);
  ModelResult r;
  r.id = ext ? ext->id : "baseline";
  r.parameters = s.parameters();
  r.k = int(r.parameters.size());
  s.simulate_design(design_start(s, baseline));
  std::vector<char> all(obs.conditions.size(), 1);
  s.trace_valley(all, kValleyPasses);
  SurfaceMinimum full = s.fit(all, nullptr, refine_points(s));
  r.dropped_early = baseline && clearly_worse(c, full.score, *baseline, r.k);
  Prediction held = c.heldout_available && r.k > 0 ? held_out(c, s, r.dropped_early, full) : Prediction{};
  if (!r.dropped_early) full = s.fit(all, nullptr, 2);  // the held-out points refine the surface
  r.params = s.values(full.u);
  // A smooth model's fit is simulated where it lies; a chaotic one's is the surface's.
  Prediction fitted = s.chaotic() ? full.prediction : s.simulate(full.u);
  r.fit_chi2 = chi_square(obs, fitted, all);
  r.prediction = fitted;
  r.chi2 = r.fit_chi2;
  if (s.stochastic() && !r.dropped_early) {  // scored on fresh replicates
    r.prediction = c.predictor.predict(ext, r.params, all, c.predictor.confirmation_first(),
                                       c.predictor.confirmation_replicates());
    r.chi2 = chi_square(obs, r.prediction, all);
  }
  r.predicted = r.prediction.mean;
  if (c.scatter_scored)
    for (size_t g = 0; g < obs.groups.size(); ++g)
      r.predicted_sd.push_back(std::sqrt(obs.groups[g].sd * obs.groups[g].sd + r.prediction.var[g]));
  r.aic = r.chi2 + 2.0 * r.k;
  // A model without parameters predicts a left-out condition as it predicts every condition.
  if (c.heldout_available) score_held_out(obs, r.k > 0 ? held : r.prediction, r);
  r.at_bound = parameters_at_bound(r, baseline ? baseline->k : r.k);
  r.points = int(s.points());
  return r;
}

void compare_with_baseline(DiagnosisContext& c, ModelResult& r, const ModelResult& base) {
  const Observations& obs = c.obs;
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
  r.p = stats::f_upper_tail(r.f, dk, c.noise_df);
  r.heldout_gain = c.heldout_available && base.heldout_sds > 0 ? 100.0 * (1.0 - r.heldout_sds / base.heldout_sds) : 0.0;
  r.standing = candidate_standing(r.p, r.heldout_gain, c.heldout_available, r.aic < base.aic,
                                  baseline_strained(base, r, c.case_values));
  r.significant = r.standing == Standing::Beats;
}

Standing candidate_standing(double p, double gain, bool heldout_available, bool aic_better, bool strained) {
  if (!heldout_available) return p < kDiagnosisSignificance ? Standing::Beats : Standing::NoBetter;
  if (p < kDiagnosisSignificance) return gain > 0 ? Standing::Beats : Standing::HeldOutAgainst;
  if ((p < kModestSignificance && gain > 0) || (aic_better && gain >= kLargeGainPercent))
    return Standing::ModestSupport;
  if (strained && gain >= kLargeGainPercent) return Standing::StrainedBaseline;
  return Standing::NoBetter;
}

std::vector<BoundFit> parameters_at_bound(const ModelResult& r, int baseline_k) {
  std::vector<BoundFit> out;
  for (size_t k = 0; k < r.params.size(); ++k) {
    const FreeParameter& p = r.parameters[k];
    double u = p.to_unit(r.params[k]);
    // An extension's own strength at its low end is the extension nearly off: unremarkable.
    bool low = u <= kOnBound && int(k) < baseline_k, high = u >= 1 - kOnBound;
    if (low || high) out.push_back({p.name, r.params[k], p.lo, p.hi, high});
  }
  return out;
}

bool baseline_strained(const ModelResult& base, const ModelResult& candidate, const std::vector<double>& case_values) {
  for (size_t k = 0; k < base.params.size() && k < candidate.params.size() && k < case_values.size(); ++k) {
    const FreeParameter& p = base.parameters[k];
    double ub = p.to_unit(base.params[k]), uc = p.to_unit(candidate.params[k]), u0 = p.to_unit(case_values[k]);
    bool base_on = ub <= kOnBound || ub >= 1 - kOnBound;
    bool same_bound = std::abs(ub - uc) <= kOnBound;
    if (base_on && !same_bound) return true;
    double moved = std::abs(ub - u0);
    if (moved >= kBentParameter && std::abs(uc - u0) <= moved / 2) return true;
  }
  return false;
}

CandidateFits fit_candidates(DiagnosisContext& c, const std::vector<const ModelExtension*>& testable,
                             const ModelResult& baseline) {
  CandidateFits out;
  for (const ModelExtension* ext : testable) {
    out.tried.push_back(ext->id);
    try {
      ModelResult r = fit_and_hold_out(c, ext, &baseline);
      compare_with_baseline(c, r, baseline);
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

}  // namespace repose
