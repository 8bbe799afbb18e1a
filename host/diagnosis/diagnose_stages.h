// The stages of `repose diagnose` (diagnose.h), each a function that returns data; diagnose()
// runs them in order and the report (diagnosis_report.h) puts the results into words. A new
// test of the baseline or a new rule for the verdict is one more stage or a change to one.
#pragma once
#include <chrono>
#include <string>
#include <vector>

#include "diagnosis/diagnose.h"

namespace repose {

// Progress of the fits on stderr: "fit 3/19 <what>, elapsed, ETA".
class FitProgress {
 public:
  FitProgress(int total, bool enabled);
  void next(const std::string& what);
  double seconds() const;

 private:
  int total_, done_ = 0;
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
};

// What every stage reads: the data, the simulations, and facts about the data.
struct DiagnosisContext {
  DiagnosisContext(const Observations& o, Predictor& p) : obs(o), predictor(p) {}
  const Observations& obs;
  Predictor& predictor;
  FitProgress* progress = nullptr;
  bool heldout_available = false;  // leave-one-condition-out needs >= 3 conditions
  bool scatter_scored = false;     // the file gives sigma: replicate scatter is compared too
  std::string primary_measure, primary_unit;
  int noise_df = 0;                // the smallest df of the noise over the measures
};

// Facts about the data the stages share (the context without its predictor and progress). Throws
// DataError when the data has too few measured means to test anything beyond the baseline.
DiagnosisContext describe_data(const Observations& obs, Predictor& predictor);

// Which candidate extensions the data can speak to (`requested` empty: all); the others come
// back untested with the reason. Throws std::runtime_error for a requested id that is unknown.
struct CandidateSelection {
  std::vector<const ModelExtension*> testable;
  std::vector<ModelResult> untestable;
};
CandidateSelection select_candidates(const Observations& obs, const std::vector<std::string>& requested,
                                     bool scatter_scored);

// Fits a model (nullptr: the baseline) to every condition, then, with >= 3 conditions, to all
// but one in turn, predicting the one left out. Extensions start from the baseline's values. A
// stochastic model is then scored on Predictor::confirmation_replicates() fresh replicates: a heap
// redraws its fills' outcomes at every parameter change, so the fit's best score is the luckiest
// of its redraws (a dry heap's chi^2 43.7 fell to 5.2 at a cohesion of Bond number 0.01).
// Its prediction and chi2 are then the fresh ones.
ModelResult fit_and_hold_out(DiagnosisContext& c, const ModelExtension* extension, const ModelResult* baseline);

// The baseline's lack of fit: overall (first) and per measure, F tests against the noise.
std::vector<LackOfFit> lack_of_fit(const Observations& obs, const ModelResult& baseline, int noise_df);

// Weighted regressions of the baseline's residuals on every condition variable (and t in a series),
// each residual weighed by the variance of the measured mean and of the predicted one.
std::vector<Trend> residual_trends(const Observations& obs, const Prediction& predicted);

// Every testable candidate fitted and compared with the baseline, in order. A candidate whose
// experiment cannot be simulated to the end (e.g. a heap that never settles under it) comes back
// untested with the reason; the others still count.
struct CandidateFits {
  std::vector<ModelResult> fitted;
  std::vector<ModelResult> failed;
  std::vector<std::string> tried;  // ids of both, in the order they were fitted
};
CandidateFits fit_candidates(DiagnosisContext& c, const std::vector<const ModelExtension*>& testable,
                             const ModelResult& baseline);

// A candidate against the baseline: extra-sum-of-squares F test, and significant when it also
// predicts held-out conditions better. A stochastic candidate is scored with its change from the
// baseline shrunk by the simulations' scatter (model_fit.h shrink_change). Its chi2 and AIC are
// the worst of its fit's own, its fresh replicates' and its shrunk change's: a fresh draw that
// happens to suit it better than its fit's (a clump's orientations), like the shrinking, only
// takes away.
void compare_with_baseline(const Observations& obs, ModelResult& candidate, const ModelResult& baseline, int noise_df,
                           bool heldout_available);

// Rivals refitted to the predictions of candidates they might stand in for: among the candidates
// that beat the baseline, each to each; one that improves on the baseline (lower AIC) without
// beating it, to the best significant one only (it is no cause of its own). Empty when no
// candidate beats the baseline.
std::vector<MimicTest> mimic_tests(DiagnosisContext& c, const ModelResult& baseline,
                                   const std::vector<ModelResult>& fitted);

// The same as a table of pairs: which these data can tell apart.
std::vector<PairSeparation> pair_separations(const std::vector<MimicTest>& mimics);

// Untested candidates that might explain the baseline's lack of fit: their simulation failed (or
// they could not be filled), yet they act on a measured quantity. None without a lack of fit.
std::vector<std::string> untested_rivals(const Observations& obs, const std::vector<ModelResult>& failed,
                                         const std::vector<LackOfFit>& lack);

// The verdict: no significant candidate is "adequate", or "unexplained" when the baseline's lack of
// fit is significant all the same; the significant one with the lowest AIC is the cause, unless a rival can mimic its predictions or an untested candidate might explain the
// data as well ("ambiguous", with what would separate them).
struct Verdict {
  std::string verdict;
  std::vector<std::string> cause;
  int winner = -1;  // index into the fitted candidates, -1 when adequate
  std::vector<MimicTest> mimics;
  double separation_chi2 = -1;
  Separation separation;
};
Verdict decide_verdict(DiagnosisContext& c, const ModelResult& baseline, const std::vector<ModelResult>& fitted,
                       const std::vector<MimicTest>& mimics, const std::vector<std::string>& untested,
                       const std::vector<LackOfFit>& lack_of_fit);

// Akaike weights of the baseline, the fitted candidates and the untested rivals (each given the
// best AIC), and the weight of what the verdict names (Diagnosis::confidence).
struct Confidence {
  std::vector<std::pair<std::string, double>> weights;
  double named = 0;
};
Confidence verdict_confidence(const ModelResult& baseline, const std::vector<ModelResult>& fitted, const Verdict& v,
                              const std::vector<std::string>& untested);

// Held-out error of the primary measure, baseline and the extended model (the winner, or the
// baseline again when adequate), and the gain in percent.
struct HeldOutGain {
  double baseline = 0, extended = 0, percent = 0;
};
HeldOutGain heldout_gain(const DiagnosisContext& c, const ModelResult& baseline, const Verdict& v,
                         const std::vector<ModelResult>& fitted);

}  // namespace repose
