// The findings of a diagnosis in plain words, built from the stages' results (diagnose_stages.h).
#include <algorithm>
#include <cstdio>

#include "diagnosis/diagnosis_report.h"
#include "diagnosis/extensions.h"
#include "util/number_text.h"

namespace repose {

namespace {

std::string num(double v, int digits = 4) { return format_g(v, digits); }

// A length in mm, anything else in its own unit.
std::string in_unit(double v, const std::string& unit) {
  if (unit == "m") return num(v * 1000, 3) + " mm";
  return num(v, 3) + (unit == "1" ? "" : " " + unit);
}

// "name = value, ..." of a model's fitted parameters.
std::string fitted_values(const ModelResult& r) {
  std::string fitted;
  for (size_t k = 0; k < r.params.size(); ++k) fitted += (k ? ", " : "") + r.parameters[k].name + " = " + num(r.params[k]);
  return fitted;
}

std::string baseline_statement(const Observations& obs, const Diagnosis& d) {
  std::string fitted = fitted_values(d.baseline);
  return "Baseline (" + d.baseline_model + "): " + (fitted.empty() ? std::string("parameters as given") : "fitted " + fitted) +
         "; chi^2 = " + num(d.baseline.chi2) + " over " + std::to_string(obs.groups.size()) +
         " measured means, weighed by their replicate scatter" +
         (d.scatter_scored ? std::string(", and their replicate variances against the given sigma (the scatter is "
                                         "data too)")
                           : std::string()) +
         ".";
}

std::string lack_of_fit_statement(const LackOfFit& overall) {
  if (overall.p < kDiagnosisSignificance)
    return "Lack of fit: the baseline misses the measured means by more than their replicate scatter allows "
           "(chi^2/df = " + num(overall.chi2 / overall.df, 3) + ", F test p = " + num(overall.p, 2) + ").";
  return "No lack of fit: the baseline agrees with the measured means within their replicate scatter (chi^2/df = " +
         num(overall.chi2 / overall.df, 3) + ", p = " + num(overall.p, 2) + ").";
}

std::string trend_statement(const Trend& t) {
  std::string unit = unit_of(t.measure);
  std::string per = t.variable == "t" ? "s" : t.variable.substr(t.variable.rfind('.') + 1);
  if (!(t.p < kDiagnosisSignificance))
    return "No significant trend of " + t.measure + " residuals with " + t.variable + " (p = " + num(t.p, 2) + ").";
  return "Residuals of " + t.measure + " (measured - simulated) " + (t.slope > 0 ? "rise" : "fall") + " with " +
         (t.variable == "t" ? "time in the series" : t.variable) + ": slope " + num(t.slope, 3) + " " + unit + " per " +
         per + " (z = " + num(t.z, 3) + ", p = " + num(t.p, 2) + "): the baseline " +
         (t.slope > 0 ? "under" : "over") + "-predicts at large " + (t.variable == "t" ? "t" : per) + ".";
}

// "repose_angle 1.31 deg vs 1.06 deg, bed_height 1.1 mm vs 4.0 mm": a candidate's held-out error
// per measure against the baseline's.
std::string per_measure(const ModelResult& r, const ModelResult& base) {
  std::string out;
  for (size_t m = 0; m < r.heldout_by_measure.size() && m < base.heldout_by_measure.size(); ++m) {
    const MeasureError &e = r.heldout_by_measure[m], &b = base.heldout_by_measure[m];
    std::string unit = unit_of(e.measure);
    out += (out.empty() ? "" : ", ") + e.measure + " " + in_unit(e.rms, unit) + " vs " + in_unit(b.rms, unit);
  }
  return out;
}

// What the tests say of a candidate, in the one meaning of "beats the baseline".
std::string standing_words(const ModelResult& r) {
  std::string gain = num(std::abs(r.heldout_gain), 3) + " % " + (r.heldout_gain >= 0 ? "less" : "more") + " held-out error";
  switch (r.standing) {
    case Standing::Beats: return "beats the baseline (F test p < 1 %, " + gain + ").";
    case Standing::HeldOutAgainst:
      return "does not beat the baseline: its F test favours it (p < 1 %), but it predicts held-out conditions no "
             "better (" + gain + ").";
    case Standing::ModestSupport:
      return "does not beat the baseline by the rule (F test p = " + num(r.p, 2) + ", above 1 %), yet predicts "
             "held-out conditions better (" + gain + ") and has the lower AIC: modest evidence for it.";
    case Standing::StrainedBaseline:
      return "does not beat the baseline by the rule (F test p = " + num(r.p, 2) + "), yet predicts held-out "
             "conditions far better (" + gain + ") where the baseline strains (below): evidence for it.";
    case Standing::NoBetter: break;
  }
  if (r.heldout_gain > 0)
    return "does not beat the baseline (F test p = " + num(r.p, 2) + "; " + gain + ", not enough to outweigh it).";
  return "is no better than the baseline (F test p = " + num(r.p, 2) + "; " + gain + ").";
}

std::string candidate_statement(const Diagnosis& d, const ModelResult& r) {
  if (!r.simulation_error.empty()) return r.id + ": not tested, its simulation failed (" + r.simulation_error + ").";
  const ModelResult& base = d.baseline;
  // A stochastic candidate is scored on fresh replicates, its change from the baseline shrunk.
  std::string scored = r.dropped_early
                           ? " (clearly worse on its " + std::to_string(r.points) +
                                 "-point design: not refined, its score and held-out errors read from its surrogate)"
                       : r.prediction.replicates > 1
                           ? " (fresh replicates; its change from the baseline, chi^2 " + num(r.change_d2, 3) +
                                 " against the simulations' scatter, kept at " + num(r.shrinkage, 2) + ")"
                           : std::string();
  return r.id + ": " + fitted_values(r) + "; chi^2 " + num(base.chi2) + " -> " + num(r.chi2) + scored + " (F = " + num(r.f, 3) +
         ", p = " + num(r.p, 2) + "), AIC " + num(base.aic) + " -> " + num(r.aic) +
         (d.heldout_available ? "; held-out error " + num(r.heldout_sds, 3) + " vs " + num(base.heldout_sds, 3) +
                                    " standard errors over every measure (" + per_measure(r, base) + "), so it "
                              : std::string(", so it ")) +
         standing_words(r);
}

// A model's fitted parameters on a bound: for the baseline evidence of an effect, and no calibration.
std::string bound_statement(const ModelResult& r, bool baseline) {
  std::string list;
  for (const BoundFit& b : r.at_bound)
    list += (list.empty() ? "" : ", ") + b.parameter + " at " + num(b.value) + ", the " + (b.upper ? "top" : "bottom") +
            " of its search range (" + num(b.lo) + "-" + num(b.hi) + ")";
  if (baseline)
    return "The baseline's fit lies on a bound: " + list + ". The baseline strains to explain the data: that is "
           "evidence for an effect, and its fitted values are not a calibration.";
  return r.id + "'s fit lies on a bound: " + list + ": its best value may lie beyond the range searched.";
}

// How far the baseline's fit moved its parameters from the case's values (a tenth of the range or
// more), where the named (or best) candidate keeps them.
std::string moved_statement(const Diagnosis& d, const ModelResult& other) {
  std::string moved;
  for (size_t k = 0; k < d.baseline.params.size() && k < d.case_values.size() && k < other.params.size(); ++k) {
    const FreeParameter& p = d.baseline.parameters[k];
    double shift = std::abs(p.to_unit(d.baseline.params[k]) - p.to_unit(d.case_values[k]));
    if (shift < 0.1) continue;  // within a tenth of its range: a calibration's refinement, not a strain
    moved += (moved.empty() ? "" : "; ") + p.name + " from the case's " + num(d.case_values[k]) + " to " +
             num(d.baseline.params[k]) + " (" + num(100 * shift, 2) + " % of its range), where " + other.id +
             " keeps it at " + num(other.params[k]);
  }
  return moved.empty() ? "" : "The baseline's fit moved " + moved + ".";
}

const ModelResult* candidate(const Diagnosis& d, const std::string& id) {
  for (const auto& c : d.candidates)
    if (c.id == id) return &c;
  return nullptr;
}

// The candidate the baseline's parameters are compared with: the named cause, else the fitted
// candidate with the lowest AIC.
const ModelResult* compared_candidate(const Diagnosis& d) {
  if (!d.cause.empty()) return candidate(d, d.cause[0]);
  const ModelResult* best = nullptr;
  for (const auto& c : d.candidates)
    if (c.tested && c.simulation_error.empty() && (!best || c.aic < best->aic)) best = &c;
  return best;
}

// "air_drag (needs a series), shape (needs sigma)": the candidates the data could not test.
std::string untested_list(const Diagnosis& d) {
  std::string list;
  for (const auto& c : d.candidates)
    if (!c.tested || !c.simulation_error.empty())
      list += (list.empty() ? "" : "; ") + c.id + " (" + (c.simulation_error.empty() ? c.untested_reason : "simulation failed") + ")";
  return list;
}

void verdict_statements(const Diagnosis& d, std::vector<std::string>& out) {
  if (d.verdict == "adequate") {
    out.push_back("Verdict: the baseline is adequate: it fits the data within the replicate scatter, and no candidate "
                  "extension explains the data better (each fails the F test at 1 % or the held-out comparison).");
  } else if (d.verdict == "unexplained") {
    std::string tried;
    for (const auto& id : d.tried) tried += (tried.empty() ? "" : ", ") + id;
    std::string untested = untested_list(d);
    std::string not_asked;  // left out by --candidates
    for (const auto& e : model_extensions())
      if (!candidate(d, e.id)) not_asked += (not_asked.empty() ? "" : ", ") + e.id;
    if (!not_asked.empty()) untested += (untested.empty() ? "" : "; ") + not_asked + " (not asked for by --candidates)";
    out.push_back("Verdict: unexplained. The baseline misses the data (lack of fit p = " + num(d.lack_of_fit.front().p, 2) +
                  "), and no candidate tested removes that: tried " + (tried.empty() ? std::string("none") : tried) +
                  "; not tested " + (untested.empty() ? std::string("none") : untested) +
                  ". The cause lies outside what was tested: test the others (with the measures they need) or look "
                  "beyond the candidates.");
  } else if (d.verdict == "effect") {
    out.push_back("Verdict: effect. The cause is " + d.cause[0] + " (" + fitted_values(*candidate(d, d.cause[0])) + ").");
  } else if (d.cause.size() == 1 + d.untested_rivals.size() && !candidate(d, d.cause[0])->significant) {
    const ModelResult& named = *candidate(d, d.cause[0]);
    out.push_back("Verdict: ambiguous. The evidence for " + named.id + " (" + fitted_values(named) +
                  ") disagrees: it " + standing_words(named) + " The baseline is not adequate while that stands. " +
                  "To decide, measure " + d.separating_measurement + ".");
  } else if (d.separation.kind == Separation::Kind::Untested) {
    std::string names;
    for (const auto& c : d.untested_rivals) names += (names.empty() ? "" : " and ") + c;
    out.push_back("Verdict: ambiguous. " + d.cause[0] + " (" + fitted_values(*candidate(d, d.cause[0])) +
                  ") beats the baseline, but " + names + " could not be tested and acts on the same measures: " +
                  "it might explain the data as well. " + d.separating_measurement + ".");
  } else {
    std::string names;
    for (const auto& c : d.cause) names += (names.empty() ? "" : " and ") + c;
    out.push_back("Verdict: ambiguous between " + names + ": the data cannot tell them apart. " +
                  "To separate them, measure " + d.separating_measurement + ".");
  }
  // How sure: the Akaike weight of what the verdict names, among the baseline, the candidates and
  // any untested rival (given the best AIC).
  std::string named = d.cause.empty() ? "the baseline" : d.cause[0];
  std::string others;
  for (const auto& [id, w] : d.weights)
    if (id != (d.cause.empty() ? "baseline" : d.cause[0]) && w >= 0.005)
      others += (others.empty() ? "" : ", ") + id + " " + num(w, 2);
  out.push_back("Confidence " + num(d.confidence, 2) + ": the Akaike weight of " + named +
                (others.empty() ? std::string(" (every other model below 0.005)") : " (" + others + ")") + ".");
  // A baseline outweighed in-sample: say by which candidate, and why it is not named.
  const ModelResult* heavier = compared_candidate(d);
  if (d.cause.empty() && heavier && heavier->aic < d.baseline.aic)
    out.push_back("The baseline's weight is the lower: " + heavier->id + " fits these data better (AIC " +
                  num(heavier->aic, 4) + " against " + num(d.baseline.aic, 4) + "), but " +
                  (d.heldout_available ? "predicts held-out conditions no better (" + num(heavier->heldout_gain, 3) +
                                             " % gain) and its F test gives p = " + num(heavier->p, 2)
                                       : "its F test gives p = " + num(heavier->p, 2)) +
                  ": not enough to name it.");
}

// The pairs of candidates, told apart or not.
std::string pairs_statement(const Diagnosis& d) {
  std::string apart, not_apart;
  for (const auto& p : d.pairs) {
    std::string& list = p.told_apart ? apart : not_apart;
    list += (list.empty() ? "" : ", ") + p.a + "/" + p.b;
  }
  return "These data tell apart " + (apart.empty() ? std::string("no pair") : apart) +
         (not_apart.empty() ? std::string("") : "; not " + not_apart) + " (each refitted to the other's predictions).";
}

// The held-out gain of what the verdict names, over every measure and per measure; a loss is
// stated as such, never as a gain.
std::string gain_statement(const Diagnosis& d, const ModelResult& named) {
  std::string measures;
  for (size_t m = 0; m < named.heldout_by_measure.size() && m < d.baseline.heldout_by_measure.size(); ++m) {
    const MeasureError &e = named.heldout_by_measure[m], &b = d.baseline.heldout_by_measure[m];
    double gain = b.sds > 0 ? 100 * (1 - e.sds / b.sds) : 0;
    std::string unit = unit_of(e.measure);
    measures += (measures.empty() ? "" : "; ") + e.measure + (d.scatter_scored ? " (mean and replicate SD)" : "") +
                " to " + in_unit(e.rms, unit) + " (RMS) against " + in_unit(b.rms, unit) + ", " + num(std::abs(gain), 3) +
                " % " + (gain >= 0 ? "less" : "more") + " error";
  }
  std::string over = "leaving each condition out in turn, the " + named.id + " model predicts the held-out means to " +
                     num(d.heldout_error_extended, 3) + " standard errors (RMS over every measure) against the "
                     "baseline's " + num(d.heldout_error_baseline, 3) + ": " + num(std::abs(d.gain_percent), 3) + " % " +
                     (d.gain_percent >= 0 ? "less" : "more") + " error. Per measure: " + measures + ".";
  return (d.gain_percent > 0 ? "Gain: " : "No gain: ") + over;
}

}  // namespace

std::string separation_in_words(const Separation& s, const Observations& obs) {
  switch (s.kind) {
    case Separation::Kind::None: return "";
    case Separation::Kind::MoreDropData:
      return "more replicates or a wider range of conditions (the trajectories already measured differ too little "
             "between the two)";
    case Separation::Kind::DropTrajectory:
      return "the trajectory z(t) of the drop (measure 'height' with a t column, from the camera): the two fitted "
             "models differ there by up to " + num(s.largest_difference * 1000, 3) + " mm at t = " + num(s.at_time, 3) +
             " s in condition " + s.condition + ", while their rebound heights agree";
    case Separation::Kind::WiderCondition:
      return "more replicates, or a wider range of the condition (" +
             (s.condition.empty() ? std::string("none varies yet") : s.condition) + ")";
    case Separation::Kind::SecondRig:
      return "more replicate heaps, or a second rig that loads the grains differently (a flow or a shear test): the "
             "angle and the bed height move alike under both";
    case Separation::Kind::HeapMeasure:
      return s.measure + (std::find(obs.measures.begin(), obs.measures.end(), s.measure) == obs.measures.end()
                              ? " (not measured here)"
                              : " (measured here: more heaps)") +
             ": the two fitted models differ there by " +
             (s.measure == "repose_angle" ? num(s.largest_difference, 3) + " deg"
              : s.measure == "profile_convexity" ? num(s.largest_difference, 3)
                                                 : num(s.largest_difference * 1000, 3) + " mm") +
             " on average, " + num(s.heap_sds, 2) + " SDs of one heap";
    case Separation::Kind::HeapAfterLift:
      return "the heap after the lift (repose_angle, runout, profile_convexity): a bed alone shows packing only";
    case Separation::Kind::MoreReplicates:
      return "more replicates per condition" +
             (s.replicate_factor > 0 ? " (about " + num(s.replicate_factor, 2) +
                                           " times as many bring its F test to the 1 % level if its effect is real)"
                                     : std::string()) +
             ", or more conditions";
    case Separation::Kind::Untested:
      return "To decide, make " + s.measure + " testable (its reason is in the candidates table) or measure what only "
             "the named cause changes";
    case Separation::Kind::BedHeight:
      return "the bed height before the lift (measure 'bed_height'): packing separates a size spread from rolling "
             "resistance, which the angle alone confounds";
  }
  return "";
}

std::vector<std::string> diagnosis_statements(const Observations& obs, const Diagnosis& d) {
  std::vector<std::string> out;
  out.push_back(baseline_statement(obs, d));
  for (const auto& [m, n] : obs.noise)
    if (n.inflation > 1.2)
      out.push_back("The " + m + " series' noise is correlated from frame to frame (lag-1 correlation " + num(n.lag1, 2) +
                    " of the replicates' deviations along t): the residuals are whitened as AR(1) in the score, and "
                    "the trend tests count " + num(n.inflation, 3) + " frames as one.");
  out.push_back(lack_of_fit_statement(d.lack_of_fit.front()));
  for (const Trend& t : d.trends) out.push_back(trend_statement(t));
  if (!d.baseline.at_bound.empty()) out.push_back(bound_statement(d.baseline, true));
  if (const ModelResult* other = compared_candidate(d)) {
    std::string moved = moved_statement(d, *other);
    if (!moved.empty()) out.push_back(moved);
  }
  for (const std::string& id : d.tried) {
    const ModelResult& r = *candidate(d, id);
    out.push_back(candidate_statement(d, r));
    if (!r.at_bound.empty()) out.push_back(bound_statement(r, false));
    if (r.refilled > 0)
      out.push_back(r.id + ": " + std::to_string(r.refilled) + " of its " + std::to_string(r.heaps) +
                    " heaps did not fit the case's fill box by random insertion and were filled largest grain first" +
                    (r.fill_raised > 0 ? " in the box raised by up to " + num(100 * r.fill_raised, 3) + " % of its height"
                                       : std::string()) +
                    ".");
  }
  for (const MimicTest& m : d.mimics)
    out.push_back(m.rival + " refitted to " + m.winner + "'s predictions misses them by chi^2 = " + num(m.chi2, 3) +
                  " (separable at 3 sigma above " + num(kSeparableChi2, 2) + "); AIC difference " + num(m.aic_difference, 3) + ".");
  if (!d.pairs.empty()) out.push_back(pairs_statement(d));
  verdict_statements(d, out);
  if (d.heldout_available && !d.cause.empty()) out.push_back(gain_statement(d, *candidate(d, d.cause[0])));
  return out;
}

}  // namespace repose
