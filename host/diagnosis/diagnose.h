// `repose diagnose`: what a calibrated model still gets wrong, why, and what an extension gains
// (README "Diagnosis", docs/diagnosis.md). It runs as stages that each return data
// (diagnosis/diagnose_stages.h): fit the baseline; test its lack of fit against the replicate
// scatter and the trends of its residuals; fit every candidate extension and compare it with the
// baseline (extra-sum-of-squares F test, AIC, leave-one-condition-out error on every measure, the
// baseline's parameters straining against a bound); the verdict names the winner, or "ambiguous"
// when the data's design cannot separate the best two or the evidence for one disagrees, or
// "adequate", or "unexplained" when the baseline misses the data and no tested candidate removes
// that. Fits run on a surrogate of each model's simulations (surrogate.h). The findings in words
// are written from those results (diagnosis_report.h).
#pragma once
#include <string>
#include <vector>

#include "diagnosis/model_fit.h"

namespace repose {

// Tests of the diagnosis are made at 1 %: lack of fit, residual trends, a candidate against the
// baseline.
constexpr double kDiagnosisSignificance = 0.01;
// chi^2 by which a rival refitted to the winner's predictions must miss them to be told apart
// (3 sigma).
constexpr double kSeparableChi2 = 9.0;
// Modest in-sample support: an F test below this, with less held-out error, is evidence the verdict
// must not overrule (it then names the candidate as `ambiguous`, never `adequate`).
constexpr double kModestSignificance = 0.05;
// A large held-out gain (percent less error over every measure, in standard errors): the heap
// tests' threshold, far above what a candidate that fits noise reaches.
constexpr double kLargeGainPercent = 30.0;

struct LackOfFit {
  std::string measure;  // "all" for the overall test
  double chi2 = 0;
  int groups = 0;
  int df = 0;           // groups - fitted parameters (overall), groups (per measure)
  int noise_df = 0;
  double p = 1;         // F test of chi2/df against the replicate scatter
};

struct Trend {
  std::string measure, variable;  // variable: a set: key, or "t" within the series
  double slope = 0, se = 0, z = 0, p = 1;  // weighted regression of the residuals on the variable
};

// A measure's held-out error: each condition predicted by a fit to the others.
struct MeasureError {
  std::string measure;
  double rms = 0;  // in its unit: RMS error of the mean or, with a given sigma, of the mean and the
                   // replicate SD together (2-Wasserstein distance of normals)
  double sds = 0;  // the same in standard errors of the measured mean (its replicate scatter / sqrt(n))
};

// A fitted parameter on an end of its search range: the model strains to explain the data.
struct BoundFit {
  std::string parameter;
  double value = 0, lo = 0, hi = 0;
  bool upper = false;
};

// How a candidate stands against the baseline, from every test the diagnosis computes.
enum class Standing {
  NoBetter,          // no test favours it enough
  Beats,             // F test p < 1 % and less held-out error over every measure (the one meaning)
  ModestSupport,     // F test p < 5 % and less held-out error (or a lower AIC and a large gain)
  StrainedBaseline,  // the baseline strains (a bound, a bent parameter) and the candidate gains largely
  HeldOutAgainst,    // F test p < 1 %, but it predicts held-out conditions no better
};

struct ModelResult {
  std::string id;  // "baseline" or an extension id
  bool tested = true;
  std::string untested_reason;
  std::vector<FreeParameter> parameters;
  std::vector<double> params;
  std::vector<double> predicted;       // every group, full fit (means)
  std::vector<double> predicted_sd;    // every group: predicted SD of one measured value (sigma and
                                       // the model's replicate scatter; empty without a given sigma)
  Prediction prediction;               // the full fit's prediction (means, replicate variances)
  std::vector<double> heldout;         // every group, predicted with its condition left out
  // The score that decides (F test, AIC, lack of fit). A stochastic model is scored on fresh
  // replicates its fit never saw (its fit's own score is chosen among redraws: biased low), and a
  // candidate's change from the baseline is shrunk by the simulations' scatter (model_fit.h).
  double chi2 = 0, aic = 0;
  double fit_chi2 = 0;                 // the fit's own score, on the replicates it searched
  double shrinkage = 1;                // of the change from the baseline (1: kept whole)
  double change_d2 = 0;                // that change's chi^2 against the simulations' scatter
  int k = 0;
  double f = 0, p = 1;                 // against the baseline
  std::vector<MeasureError> heldout_by_measure;  // every measure, in the data's order
  double heldout_sds = 0;              // every measure: root mean square of their errors in standard errors
  double heldout_gain = 0;             // a candidate: 100 (1 - heldout_sds / the baseline's)
  bool significant = false;            // beats the baseline (Standing::Beats)
  Standing standing = Standing::NoBetter;
  std::vector<BoundFit> at_bound;      // fitted parameters on an end of their range
  bool dropped_early = false;          // clearly worse after its design: not refined or confirmed
  int points = 0;                      // parameter points simulated (its surrogate's design)
  std::string simulation_error;        // not tested because its simulation failed: the error
  int heaps = 0, refilled = 0;         // heaps simulated, and those whose grains did not fit the case's
  double fill_raised = 0;              // fill box by random insertion (heap_fill.h), and the most its box
                                       // was raised by (fraction of its height)
};

// Can a rival candidate mimic the winner? The rival refitted to the winner's predictions.
struct MimicTest {
  std::string rival, winner;
  double chi2 = 0;             // how far the refitted rival stays from the winner's predictions
  double aic_difference = 0;   // rival's AIC - winner's
  bool close = false;          // too close to tell apart: the rival joins the cause
};

// What would tell two close candidates apart (an ambiguous verdict).
struct Separation {
  enum class Kind {
    None,
    DropTrajectory,    // drop data without a series: the camera's track, where the two differ most
    MoreDropData,      // drop data with a series: more replicates or a wider range
    WiderCondition,    // tilt and roll: more replicates or a wider range of the condition
    BedHeight,         // heap angles alone: the bed height before the lift
    SecondRig,         // heap measures that both models predict alike: another rig
    HeapMeasure,       // the heap measure (measured or not) where the two fitted models differ most
    HeapAfterLift,     // bed heights alone: the heap after the lift (angle, run-out, convexity)
    Untested,          // a candidate that might explain the data could not be tested
    MoreReplicates,    // the evidence for one candidate disagrees: more replicates would decide
  } kind = Kind::None;
  double replicate_factor = 0;    // MoreReplicates: about how many times the replicates the F test needs
  std::string measure;            // HeapMeasure: which; Untested: the candidate
  double heap_sds = 0;            // HeapMeasure: the difference in SDs of one simulated heap
  double largest_difference = 0;  // DropTrajectory: m, between the two fitted trajectories
  double at_time = 0;             // s, where
  std::string condition;          // the condition compared (its label), or the condition variable
};

// Can the data tell two candidates apart? Each refitted to the other's predictions (a rival that
// does not beat the baseline is only refitted to the winner's: it is no cause of its own).
struct PairSeparation {
  std::string a, b;
  double a_as_b = -1;       // chi^2 by which a, refitted to b's predictions, misses them (-1: not tried)
  double b_as_a = -1;
  bool told_apart = false;  // no tried direction is close (MimicTest::close)
};

struct Diagnosis {
  std::string verdict;             // adequate | unexplained | effect | ambiguous
  std::vector<std::string> cause;  // one id (effect), two or more (ambiguous), none (adequate,
                                   // unexplained: the baseline misses the data, no candidate helps)
  std::string baseline_model;      // the experiment's baseline, in words
  ModelResult baseline;
  std::vector<ModelResult> candidates;  // untestable ones first, then those whose simulation
                                        // failed, then the fitted ones, each in table order
  std::vector<std::string> tried;  // candidates fitted (or whose simulation failed), in order
  std::vector<MimicTest> mimics;   // effect or ambiguous: each rival that improves on the baseline
  std::vector<PairSeparation> pairs;  // which candidates these data can tell apart
  // Untested candidates that might explain the lack of fit (their simulation failed, or they are
  // not simulated yet, yet they act on a measured quantity): they keep a verdict from naming one
  // cause.
  std::vector<std::string> untested_rivals;
  // Akaike weights (exp(-AIC/2), normalised) of the baseline and every fitted candidate, with each
  // untested rival given the best AIC (it might do as well); `confidence` is the weight of the
  // named cause (effect, ambiguous: the first), or of the baseline (adequate, unexplained).
  std::vector<std::pair<std::string, double>> weights;
  double confidence = 0;
  std::vector<LackOfFit> lack_of_fit;
  std::vector<Trend> trends;
  // The baseline's strain: its fitted parameters on a bound, and how far the fit moved them from
  // the case's values (where the named or best candidate keeps them).
  std::vector<double> case_values;   // the baseline's parameters as the case gives them
  bool heldout_available = false;  // leave-one-condition-out needs >= 3 conditions
  bool scatter_scored = false;     // the file gives sigma: replicate scatter is compared too
  // Held-out error over every measure in standard errors (MeasureError::sds), of the baseline and
  // of what the verdict names (the baseline again when it names none), and the gain in percent;
  // per measure in the named model's and the baseline's heldout_by_measure.
  double heldout_error_baseline = 0, heldout_error_extended = 0, gain_percent = 0;
  double separation_chi2 = -1;     // how well the closest rival mimics the winner
  Separation separation;           // ambiguous: what would tell the two apart
  std::string separating_measurement;   // the same in words
  std::vector<std::string> statements;  // the findings in plain words, in report order
  size_t simulations = 0;
  double seconds = 0;
};

struct DiagnoseOptions {
  std::vector<CaseOverride> given;    // --params: calibrated values (the baseline is then not refitted)
  bool fit_baseline = true;           // the baseline's free parameter (Predictor) is fitted
  unsigned threads = 2;
  std::vector<std::string> candidates;  // empty: every extension the data's measures can reveal
  int simulated_replicates = 8;         // per condition, for a model whose drop is stochastic (shape)
  bool progress = true;  // the cost estimate before, and progress with an ETA on stderr
};

Diagnosis diagnose(const Observations& obs, const DiagnoseOptions& options);

}  // namespace repose
