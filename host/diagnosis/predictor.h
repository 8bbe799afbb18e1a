// Simulated values of the measured quantities: every condition of the data is run as its virtual
// experiment (the drop test) with the model under test, on the cpu backend, conditions spread
// over a few threads, each result cached by (condition, model, parameters) for the whole run.
#pragma once
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "diagnosis/extensions.h"
#include "diagnosis/observations.h"
#include "experiments/drop.h"

namespace repose {

class Predictor {
 public:
  // `given`: calibrated parameters (case overrides) applied to every case before its row's sets.
  // `fit_restitution`: the baseline's free parameter (the body-plate restitution) is fitted;
  // otherwise it stays at the case's (or given) value.
  Predictor(const Observations& obs, std::vector<CaseOverride> given, bool fit_restitution, unsigned threads);

  // The parameters a model fits, in order: the baseline's free ones, then the extension's.
  std::vector<FreeParameter> parameters(const ModelExtension* extension) const;
  bool fits_restitution() const { return fit_restitution_; }
  double case_restitution() const;  // of the first condition's case (the start of a fit)

  // The predicted value of every group whose condition is marked in `use` (others: 0).
  std::vector<double> predict(const ModelExtension* extension, const std::vector<double>& params,
                              const std::vector<char>& use);
  // One condition's drop (cached). Thread-safe.
  DropResult drop(size_t condition, const ModelExtension* extension, const std::vector<double>& params);
  // The value of one group from a drop result.
  double value_of(const ObservationGroup& g, const DropResult& r) const;

  const Observations& observations() const { return obs_; }
  size_t simulations() const { return simulations_; }

 private:
  const Observations& obs_;
  std::vector<CaseSpec> specs_;  // per condition, loaded once
  bool fit_restitution_;
  unsigned threads_;
  std::mutex mutex_;
  std::map<std::string, DropResult> cache_;
  size_t simulations_ = 0;
};

}  // namespace repose
