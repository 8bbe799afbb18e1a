#include "diagnosis/diagnose.h"

#include <cstdio>

#include "diagnosis/diagnose_stages.h"
#include "diagnosis/diagnosis_report.h"

namespace repose {

Diagnosis diagnose(const Observations& obs, const DiagnoseOptions& options) {
  Predictor predictor(obs, options.given, options.fit_baseline, options.threads, options.simulated_replicates);
  DiagnosisContext c = describe_data(obs, predictor);
  Diagnosis d;
  d.baseline_model = predictor.role().baseline_model;
  d.heldout_available = c.heldout_available;
  d.scatter_scored = c.scatter_scored;
  d.case_values = c.case_values;

  CandidateSelection selection = select_candidates(obs, options.candidates, c.scatter_scored);
  d.candidates = selection.untestable;
  size_t planned = planned_simulations(c, selection.testable);
  if (options.progress) {
    std::string models = "baseline";
    for (const ModelExtension* e : selection.testable) models += ", " + e->id;
    std::fprintf(stderr, "diagnose: %zu models (%s) on %zu conditions: about %zu simulations planned\n",
                 1 + selection.testable.size(), models.c_str(), obs.conditions.size(), planned);
  }
  SimulationProgress progress(predictor, planned, options.progress);
  c.progress = &progress;

  // 1. The baseline and what is wrong with it.
  d.baseline = fit_and_hold_out(c, nullptr, nullptr);
  d.lack_of_fit = lack_of_fit(obs, d.baseline, c.noise_df);
  d.trends = residual_trends(obs, d.baseline.prediction);
  // 2. Every candidate extension, fitted and compared with the baseline.
  CandidateFits fits = fit_candidates(c, selection.testable, d.baseline);
  d.candidates.insert(d.candidates.end(), fits.failed.begin(), fits.failed.end());
  d.tried = fits.tried;
  // 3. The verdict, and what the winner gains on held-out conditions.
  std::vector<MimicTest> mimics = mimic_tests(c, d.baseline, fits.fitted);
  d.pairs = pair_separations(mimics);
  d.untested_rivals = untested_rivals(obs, fits.failed, d.lack_of_fit);
  Verdict verdict = decide_verdict(c, d.baseline, fits.fitted, mimics, d.untested_rivals, d.lack_of_fit);
  Confidence confidence = verdict_confidence(d.baseline, fits.fitted, verdict, d.untested_rivals);
  d.weights = confidence.weights;
  d.confidence = confidence.named;
  d.verdict = verdict.verdict;
  d.cause = verdict.cause;
  d.mimics = verdict.mimics;
  d.separation_chi2 = verdict.separation_chi2;
  d.separation = verdict.separation;
  HeldOutGain gain = heldout_gain(c, d.baseline, verdict, fits.fitted);
  d.heldout_error_baseline = gain.baseline;
  d.heldout_error_extended = gain.extended;
  d.gain_percent = gain.percent;
  d.candidates.insert(d.candidates.end(), fits.fitted.begin(), fits.fitted.end());
  d.simulations = predictor.simulations();
  d.seconds = progress.seconds();
  // 4. The findings in words.
  d.separating_measurement = separation_in_words(d.separation, obs);
  d.statements = diagnosis_statements(obs, d);
  return d;
}

}  // namespace repose
