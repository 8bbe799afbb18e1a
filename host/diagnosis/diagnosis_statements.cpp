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

std::string candidate_statement(const Diagnosis& d, const ModelResult& r) {
  if (!r.simulation_error.empty()) return r.id + ": not tested, its simulation failed (" + r.simulation_error + ").";
  const ModelResult& base = d.baseline;
  // A stochastic candidate is scored on fresh replicates, its change from the baseline shrunk.
  std::string scored = r.prediction.replicates > 1
                           ? " (fresh replicates; its change from the baseline, chi^2 " + num(r.change_d2, 3) +
                                 " against the simulations' scatter, kept at " + num(r.shrinkage, 2) + ")"
                           : std::string();
  return r.id + ": " + fitted_values(r) + "; chi^2 " + num(base.chi2) + " -> " + num(r.chi2) + scored + " (F = " + num(r.f, 3) +
         ", p = " + num(r.p, 2) + "), AIC " + num(base.aic) + " -> " + num(r.aic) +
         (d.heldout_available ? ", held-out error " + in_unit(r.heldout_rms, d.primary_unit) + " vs " +
                                    in_unit(base.heldout_rms, d.primary_unit) + " (baseline)"
                              : std::string()) +
         (r.significant ? ": beats the baseline." : ": no better than the baseline.");
}

const ModelResult* candidate(const Diagnosis& d, const std::string& id) {
  for (const auto& c : d.candidates)
    if (c.id == id) return &c;
  return nullptr;
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
  for (const std::string& id : d.tried) {
    const ModelResult& r = *candidate(d, id);
    out.push_back(candidate_statement(d, r));
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
  if (d.heldout_available && !d.cause.empty())
    out.push_back("Gain: leaving each condition out in turn, the " + d.cause[0] + " model predicts " + d.primary_measure +
                  (d.scatter_scored ? " (mean and replicate SD)" : "") + " to " +
                  in_unit(d.heldout_error_extended, d.primary_unit) + " (RMS), the baseline to " +
                  in_unit(d.heldout_error_baseline, d.primary_unit) + ": " + num(d.gain_percent, 3) + " % less error.");
  return out;
}

}  // namespace repose
