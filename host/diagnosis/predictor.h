// Simulated values of the measured quantities: every condition of the data is run as its virtual
// experiment (the drop test) with the model under test, on the cpu backend, conditions spread
// over a few threads, each result cached by (condition, model, parameters, replicate) for the run.
//
// A model whose body is a clump (extension `shape`) lands at a random orientation, so its drop is
// stochastic: it is simulated `simulated_replicates` times per condition, replicate r with the
// case's seed + r in every evaluation (common random numbers: the same orientations whatever the
// parameters, so the objective stays smooth), and predicts both the mean and the replicate
// variance of one value. A sphere's drop is deterministic: one run, variance 0.
#pragma once
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "diagnosis/extensions.h"
#include "diagnosis/observations.h"
#include "experiments/drop.h"

namespace repose {

struct Prediction {
  std::vector<double> mean;  // every group (0 where its condition was not asked for)
  std::vector<double> var;   // the model's replicate variance of one value (0: deterministic)
  int replicates = 1;        // simulated replicates behind each mean
};

class Predictor {
 public:
  // `given`: calibrated parameters (case overrides) applied to every case before its row's sets.
  // `fit_restitution`: the baseline's free parameter (the body-plate restitution) is fitted;
  // otherwise it stays at the case's (or given) value.
  Predictor(const Observations& obs, std::vector<CaseOverride> given, bool fit_restitution, unsigned threads,
            int simulated_replicates = 8);

  // The parameters a model fits, in order: the baseline's free ones, then the extension's.
  std::vector<FreeParameter> parameters(const ModelExtension* extension) const;
  bool fits_restitution() const { return fit_restitution_; }
  double case_restitution() const;  // of the first condition's case (the start of a fit)
  // Whether the model's drop depends on the replicate's seed (a clump body).
  bool stochastic(const ModelExtension* extension, const std::vector<double>& params) const;

  // The prediction for every group whose condition is marked in `use`.
  Prediction predict(const ModelExtension* extension, const std::vector<double>& params, const std::vector<char>& use);
  // One condition's drop, replicate r (cached). Thread-safe.
  DropResult drop(size_t condition, const ModelExtension* extension, const std::vector<double>& params,
                  int replicate = 0);
  // The value of one group from a drop result.
  double value_of(const ObservationGroup& g, const DropResult& r) const;

  const Observations& observations() const { return obs_; }
  size_t simulations() const { return simulations_; }
  int simulated_replicates() const { return replicates_; }

 private:
  CaseSpec model_spec(size_t condition, const ModelExtension* extension, const std::vector<double>& params,
                      int replicate) const;
  const Observations& obs_;
  std::vector<CaseSpec> specs_;  // per condition, loaded once
  bool fit_restitution_;
  unsigned threads_;
  int replicates_;
  std::mutex mutex_;
  std::map<std::string, DropResult> cache_;
  size_t simulations_ = 0;
};

}  // namespace repose
