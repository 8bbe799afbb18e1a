// The stages of `repose diagnose` (diagnose.h), each a function that returns data; diagnose()
// runs them in order and the report (diagnosis_report.h) puts the results into words. A new
// test of the baseline or a new rule for the verdict is one more stage or a change to one.
#pragma once
#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "diagnosis/diagnose.h"
#include "diagnosis/surrogate.h"

namespace repose {

// The cost before, and the progress on stderr while it runs: "diagnose: 340/1180 simulations
// (rolling_epsd), 2.9 min elapsed, ETA 7.1 min", at most every few seconds.
class SimulationProgress {
 public:
  SimulationProgress(const Predictor& predictor, size_t planned, bool enabled);
  void update(const std::string& what);
  double seconds() const;

 private:
  const Predictor& predictor_;
  size_t planned_;
  bool enabled_, estimated_ = false;
  double last_ = -1e9;
  std::chrono::steady_clock::time_point start_;
};

// What every stage reads: the data, the simulations, and facts about the data.
struct DiagnosisContext {
  DiagnosisContext(const Observations& o, Predictor& p) : obs(o), predictor(p) {}
  const Observations& obs;
  Predictor& predictor;
  SimulationProgress* progress = nullptr;
  bool heldout_available = false;  // leave-one-condition-out needs >= 3 conditions
  bool scatter_scored = false;     // the file gives sigma: replicate scatter is compared too
  int noise_df = 0;                // the smallest df of the noise over the measures
  std::vector<double> case_values;  // the baseline's fitted parameters as the cases give them
  // Each model's surrogate (by id: "baseline" or the extension's), made on first use; the fits,
  // held-out refits and mimic tests of one model share its simulated points.
  std::map<std::string, std::unique_ptr<ModelSurrogate>> surrogates;
  ModelSurrogate& surrogate(const ModelExtension* extension);
};

// Facts about the data the stages share (the context without its predictor and progress). Throws
// DataError when the data has too few measured means to test anything beyond the baseline.
DiagnosisContext describe_data(const Observations& obs, Predictor& predictor);

// The simulations the baseline and the candidates plan for (their surrogates' designs, refinement,
// held-out refits and fresh replicates): the cost estimate printed before starting.
size_t planned_simulations(DiagnosisContext& c, const std::vector<const ModelExtension*>& testable);

// Which candidate extensions the data can speak to (`requested` empty: all); the others come
// back untested with the reason. Throws std::runtime_error for a requested id that is unknown.
struct CandidateSelection {
  std::vector<const ModelExtension*> testable;
  std::vector<ModelResult> untestable;
};
CandidateSelection select_candidates(const Observations& obs, const std::vector<std::string>& requested,
                                     bool scatter_scored);

// Fits a model (nullptr: the baseline) to every condition on its surrogate, then, with >= 3
// conditions, to all but one in turn, simulating the one left out at that fit. An extension's
// design includes the baseline's values with the extension off. A candidate whose best score on its
// design cannot reach even the modest F test against the baseline is clearly worse: it is dropped
// early, its held-out predictions read from the surface. A stochastic model is then scored on
// Predictor::confirmation_replicates() fresh replicates: a heap redraws its fills' outcomes at every
// parameter change, so a fit's best score is biased low by the luck of its draws (a dry heap's
// chi^2 43.7 fell to 5.2 at a cohesion of Bond number 0.01). Its prediction and chi2 are then the
// fresh ones.
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

// A candidate against the baseline: extra-sum-of-squares F test and the held-out gain over every
// measure. A stochastic candidate is scored with its change from the baseline shrunk by the
// simulations' scatter (model_fit.h shrink_change). Its chi2 and AIC are the worst of its fit's
// own, its fresh replicates' and its shrunk change's: a fresh draw that happens to suit it better
// than its fit's (a clump's orientations), like the shrinking, only takes away. Its standing
// (Beats, ...) then follows from candidate_standing.
void compare_with_baseline(DiagnosisContext& c, ModelResult& candidate, const ModelResult& baseline);

// How a candidate stands, from its F test p, its held-out gain (percent, over every measure), its
// AIC against the baseline's and whether the baseline strains where it does not
// (baseline_strained):
//   Beats            p < 1 % and a positive gain (the one meaning of "beats the baseline");
//   HeldOutAgainst   p < 1 % but no gain: the in-sample and the held-out evidence disagree;
//   ModestSupport    p < 5 % and a positive gain, or a lower AIC and a gain of at least
//                    kLargeGainPercent: every test leans its way, none decides;
//   StrainedBaseline the baseline strains and the gain is at least kLargeGainPercent;
//   NoBetter         otherwise.
// Without held-out conditions (fewer than 3) the F test alone decides Beats or NoBetter.
Standing candidate_standing(double p, double gain_percent, bool heldout_available, bool aic_better,
                            bool baseline_strained);

// A model's fitted parameters on an end of their range (within 0.5 % of it): the first
// `baseline_k` (the baseline's) at either end, an extension's own at the top only (its low end is
// the extension nearly off). And whether the baseline strains where `candidate` does not: a
// parameter on a bound, or moved from the case's value by a quarter of its range or more while the
// candidate keeps it at most half as far.
std::vector<BoundFit> parameters_at_bound(const ModelResult& model, int baseline_k);
bool baseline_strained(const ModelResult& baseline, const ModelResult& candidate, const std::vector<double>& case_values);

// Rivals refitted to the predictions of candidates they might stand in for: among the candidates
// that beat the baseline, each to each; one that improves on the baseline (lower AIC) without
// beating it, to the best significant one only (it is no cause of its own). Empty when no
// candidate beats the baseline.
std::vector<MimicTest> mimic_tests(DiagnosisContext& c, const ModelResult& baseline,
                                   const std::vector<ModelResult>& fitted);

// A rival that comes within chi^2 kSeparableChi2 of the winner's predictions mimics it, unless the
// data themselves reject it (its AIC more than 10 above the winner's); one within 2 always does.
bool rival_mimics(double chi2, double aic_difference);

// The same as a table of pairs: which these data can tell apart.
std::vector<PairSeparation> pair_separations(const std::vector<MimicTest>& mimics);

// Untested candidates that might explain the baseline's lack of fit: their simulation failed (or
// they could not be filled), yet they act on a measured quantity. None without a lack of fit.
std::vector<std::string> untested_rivals(const Observations& obs, const std::vector<ModelResult>& failed,
                                         const std::vector<LackOfFit>& lack);

// The verdict: the candidate that beats the baseline with the lowest AIC is the cause, unless a
// rival can mimic its predictions or an untested candidate might explain the data as well
// ("ambiguous", with what would separate them). With none that beats it, a candidate whose
// evidence disagrees (Standing ModestSupport, StrainedBaseline or HeldOutAgainst; the lowest AIC
// first) is named alone as "ambiguous": more replicates would decide. Otherwise "adequate", or
// "unexplained" when the baseline's lack of fit is significant all the same.
struct Verdict {
  std::string verdict;
  std::vector<std::string> cause;
  int winner = -1;  // index into the fitted candidates of the first named, -1 when it names none
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

// Held-out error over every measure (standard errors), baseline and the named model (the cause,
// or the baseline again when none), and the gain in percent.
struct HeldOutGain {
  double baseline = 0, extended = 0, percent = 0;
};
HeldOutGain heldout_gain(const DiagnosisContext& c, const ModelResult& baseline, const Verdict& v,
                         const std::vector<ModelResult>& fitted);

}  // namespace repose
