// Simulated values of the measured quantities: every condition of the data is run as its virtual
// experiment (experiments/registry.h: the experiment its case names, which says how a diagnosis
// simulates it and what the baseline's free parameter is) with the model under test, on the cpu
// backend, spread over a few threads, each result cached by (condition, model, parameters,
// replicate) for the run.
//
// A stochastic model is simulated `simulated_replicates` times per condition, replicate r with
// seed + r in every evaluation (common random numbers: the same draws whatever the parameters, so
// the objective stays smooth), and predicts the mean and the replicate variance of one value: a
// clump body (extension `shape`) lands at a random orientation drawn from the case's seed, a heap
// is filled from its fills' seeds. A sphere's drop is deterministic: one run, variance 0.
#pragma once
#include <algorithm>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "diagnosis/extensions.h"
#include "diagnosis/observations.h"
#include "experiments/experiment.h"

namespace repose {

struct Prediction {
  std::vector<double> mean;  // every group (0 where its condition was not asked for)
  std::vector<double> var;   // the model's replicate variance of one value (0: deterministic)
  int replicates = 1;        // simulated replicates behind each mean
  // Variance of each mean from the simulations' own scatter; empty: var / replicates (a model's
  // change shrunk toward the baseline's, model_fit.h, gives its own).
  std::vector<double> mean_var;
  double variance_of_mean(size_t g) const {
    if (!mean_var.empty()) return mean_var[g];
    return replicates > 1 && !var.empty() ? var[g] / replicates : 0.0;
  }
};

// One simulated experiment: its scalar measures and, for a drop, the camera's trajectory.
using Outcome = DiagnosticOutcome;

class Predictor {
 public:
  // `given`: calibrated parameters (case overrides) applied to every case before its row's sets.
  // `fit_baseline`: the baseline's free parameter is fitted; otherwise it stays at the case's
  // (or given) value.
  Predictor(const Observations& obs, std::vector<CaseOverride> given, bool fit_baseline, unsigned threads,
            int simulated_replicates = 8);

  // The parameters a model fits, in order: the baseline's free ones, then the extension's.
  std::vector<FreeParameter> parameters(const ModelExtension* extension) const;
  bool fits_baseline() const { return fit_baseline_; }
  double case_baseline_value() const;  // of the first condition's case (the start of a fit)
  std::string experiment() const { return experiment_->id(); }  // "drop", "repose", ...
  const DiagnosisRole& role() const { return *role_; }
  // A heap costs ~1000 drops: fits then spend fewer evaluations (model_fit.cpp).
  bool expensive() const { return role_->expensive; }
  // Whether the model's result depends on the replicate's seed (a clump body, a filled heap).
  bool stochastic(const ModelExtension* extension, const std::vector<double>& params) const;

  // The prediction for every group whose condition is marked in `use`. A stochastic model is
  // simulated as replicates first_replicate ... first_replicate + replicates - 1 (replicates 0:
  // simulated_replicates()); a surrogate's design point uses 0 ... its count - 1 (a clump's common
  // orientations) or fills of its own (a heap, surrogate.h), the confirmation of a fitted model
  // fresh ones.
  Prediction predict(const ModelExtension* extension, const std::vector<double>& params, const std::vector<char>& use,
                     int first_replicate = 0, int replicates = 0);
  // One condition's experiment, replicate r (cached). Thread-safe.
  Outcome simulate(size_t condition, const ModelExtension* extension, const std::vector<double>& params,
                   int replicate = 0);
  // The value of one group from an outcome.
  double value_of(const ObservationGroup& g, const Outcome& r) const;

  // How a heap model's grains were placed (heap_fill.h), over every heap it simulated.
  struct FillRecord {
    int heaps = 0, fallback = 0;  // fallback: the case's own fill failed, placed largest first
    double most_raised = 0;       // the largest fraction its fill box was raised by
  };
  FillRecord fills(const std::string& model_id) const {
    std::lock_guard<std::mutex> lock(fill_mutex_);
    auto it = fills_.find(model_id);
    return it == fills_.end() ? FillRecord{} : it->second;
  }

  const Observations& observations() const { return obs_; }
  size_t simulations() const { return simulations_; }
  int simulated_replicates() const { return replicates_; }
  // A fitted stochastic model's confirmation: fresh fills or orientations, replicates
  // confirmation_first() ... + confirmation_replicates() - 1, none of which its fit saw
  // (diagnose_stages.h, fit_and_hold_out).
  int confirmation_first() const { return replicates_; }
  int confirmation_replicates() const { return std::max(8, 2 * replicates_); }

 private:
  // Counts a heap model's fill as placed (heap_fill.h: largest first, or in a raised box, when
  // the case's own fill found no room), from its fills against the condition's case.
  void record_fill(size_t condition, const ModelExtension* extension, const CaseSpec& spec) const;
  CaseSpec model_spec(size_t condition, const ModelExtension* extension, const std::vector<double>& params,
                      int replicate) const;
  void check_measures() const;
  const Observations& obs_;
  const Experiment* experiment_ = nullptr;
  const DiagnosisRole* role_ = nullptr;
  std::vector<CaseSpec> specs_;  // per condition, loaded once (a heap's with its fills unexpanded)
  bool fit_baseline_;
  unsigned threads_;
  int replicates_;
  std::mutex mutex_;
  std::map<std::string, Outcome> cache_;
  mutable std::mutex fill_mutex_;
  mutable std::map<std::string, FillRecord> fills_;  // by model id
  size_t simulations_ = 0;
};

}  // namespace repose
