// Fitting a model's free parameters to the measured group means: weighted least squares
// (chi^2 = sum over groups of (mean - simulated)^2 / var(mean)), minimised by Nelder-Mead in the
// unit cube of the parameters' search ranges (log ranges for strengths spanning decades).
#pragma once
#include <vector>

#include "diagnosis/predictor.h"

namespace repose {

struct ModelFit {
  std::vector<double> params;      // fitted values, in the order of Predictor::parameters
  std::vector<double> predicted;   // every group (only the fitted conditions are meaningful)
  double chi2 = 0;                 // over the fitted conditions
  int groups = 0;                  // groups in the fit
  int evaluations = 0;
};

// chi^2 of given predictions over the groups of the conditions marked in `use`, against the
// measured means or, when `target` is not empty, against those values (another model's predictions).
double chi_square(const Observations& obs, const std::vector<double>& predicted, const std::vector<char>& use,
                  const std::vector<double>& target = {});

// Fits `extension` (nullptr: the baseline) on the conditions marked in `use`, starting from
// `start` (empty: the middle of each range, the case's restitution).
ModelFit fit_model(Predictor& predictor, const ModelExtension* extension, const std::vector<char>& use,
                   const std::vector<double>& start = {}, double step = 0.15, int max_evaluations = 80,
                   const std::vector<double>& target = {});

}  // namespace repose
