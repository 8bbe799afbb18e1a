// What a campaign concludes, whichever way it got there (design + response surface, sweep +
// calibration curve, or the adaptive loop): the chosen parameters with their uncertainty, the
// verification runs, and a predictor for the report's figures.
#pragma once
#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

#include "calibrate/run_spec.h"

namespace repose::calibrate {

struct ParameterEstimate {
  std::string name;
  double value = 0;        // calibrated (actual units)
  double slope = 0;        // d response / d parameter there (actual units)
  double uncertainty = 0;  // sigma_response / |slope| (others held); inf when the slope vanishes
  double set_low = 0, set_high = 0;  // extent of the parameter sets meeting the target (others free)
};

struct CalibrationResult {
  std::string method;              // "response surface", "calibration curve", "adaptive (GP + EI)"
  Eigen::VectorXd chosen_coded;    // in the plan's factor coding (low -1, high +1)
  std::vector<double> chosen;      // actual
  double predicted = 0;            // model's response at the chosen point
  double predicted_sd = 0;         // its uncertainty (sd of the mean response; adaptive loop)
  double run_noise_sd = 0;         // run-to-run scatter the surrogate found (adaptive loop)
  bool target_reached = false;     // the model (or the loop's runs) meet the target
  std::vector<ParameterEstimate> parameters;
  double replicate_sd = 0;         // pooled sd of replicate runs (packing seeds)
  int replicate_df = 0;
  double sigma_response = 0;       // sqrt(measured_sd^2 + replicate_sd^2)
  std::vector<RunRecord> verification;
  double verification_mean = 0, verification_sd = 0, verification_error = 0;  // error relative to measured
  std::string model_text;          // ANOVA, equations or GP summary, preformatted
  // Model prediction (and its sd, may be empty) at a coded point, for the figures.
  std::function<double(const Eigen::VectorXd&)> predict;
  std::function<double(const Eigen::VectorXd&)> predict_sd;
  double coded_extent = 1;         // figures show coded [-extent, extent]
};

// Pooled standard deviation of groups of replicate responses (groups of one add nothing).
void pool_replicates(const std::vector<std::vector<double>>& groups, double& sd, int& df);

}  // namespace repose::calibrate
