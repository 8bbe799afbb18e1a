// What a campaign concludes, whichever way it got there (design + response surface, sweep +
// calibration curve, a steepest-ascent path, or the adaptive loop): the chosen parameters, the
// model of each calibrating response, the posterior of the parameters, and the verification.
#pragma once
#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

#include "calibrate/noise.h"
#include "calibrate/plan.h"
#include "calibrate/posterior.h"
#include "calibrate/run_spec.h"
#include "calibrate/verification.h"

namespace repose::calibrate {

struct ParameterEstimate {
  std::string name;
  double value = 0;        // chosen (actual units)
  double slope = 0;        // d response / d parameter there (the first calibrating response, actual units)
  double set_low = 0, set_high = 0;  // extent of the parameter sets the model puts within the tolerance
  // From the posterior (actual units): 5 %, 50 %, 95 % of the marginal, its sd, and whether the
  // data identify the parameter (its 90 % interval narrower than 80 % of the range).
  bool has_posterior = false;
  double low = 0, median = 0, high = 0, sd = 0;
  bool identified = true;
};

// One calibrating response as the model sees it.
struct ResponseModel {
  int response = 0;                                          // index into plan.responses
  std::function<double(const Eigen::VectorXd&)> predict;     // mean response at a coded point
  std::function<double(const Eigen::VectorXd&)> predict_sd;  // sd of that mean (may be empty)
  double predicted = 0, predicted_sd = 0;                    // at the chosen point
  NoiseEstimate noise;                                       // run-to-run noise from replicates
  double surrogate_noise_sd = -1;                            // the surrogate's nugget (adaptive; -1: none)
  std::vector<RunRecord> runs;                               // the runs it was fitted to
};

// A point of a steepest-ascent path: the means of its replicates, per calibrating response.
struct PathPoint {
  Eigen::VectorXd coded;
  std::vector<double> mean, se;  // per calibrating response; se NaN when the noise is unknown
  int runs = 0;
  double miss = 0;               // expected miss (expected_miss of its means)
};

struct CalibrationResult {
  std::string method;              // "response surface", "calibration curve", "steepest-ascent path", "adaptive ..."
  Eigen::VectorXd chosen_coded;    // in the plan's factor coding (low -1, high +1)
  std::vector<double> chosen;      // actual
  bool model_on_target = false;    // the model puts every calibrating response within its tolerance there
  std::vector<ResponseModel> models;  // one per calibrating response, in plan order
  std::vector<ParameterEstimate> parameters;
  Posterior posterior;             // computed unless the method fits no model (a path)
  std::string ridge_text;          // the posterior's ridge in words (empty for one factor)
  std::vector<ResponseCheck> checks;  // one per verified response
  bool target_reached = false;     // every check confirmed
  std::string model_text;          // ANOVA, equations or surrogate summary, preformatted
  double coded_extent = 1;         // figures show coded [-extent, extent]
  std::vector<PathPoint> path;     // a steepest-ascent path's points, in path order

  const ResponseModel& primary() const { return models.front(); }
};

}  // namespace repose::calibrate

namespace repose::calibrate {

// The scale a response's miss is measured in when several are combined: the lab's standard
// error, or its tolerance when the lab gave none.
double response_scale(const PlanResponse& response);

// The expected squared miss of the mean responses at a coded point, each in its own scale:
// sum_i ((mean_i - measured_i)^2 + sd_i^2) / scale_i^2.
double expected_miss(const CampaignPlan& plan, const std::vector<ResponseModel>& models, const Eigen::VectorXd& coded);

// Whether every model's mean lies within its response's tolerance at a coded point.
bool within_tolerance(const CampaignPlan& plan, const std::vector<ResponseModel>& models, const Eigen::VectorXd& coded);

// The held factors of the plan (design.fix) as coded (factor, value) pairs.
std::vector<std::pair<int, double>> held_factors(const CampaignPlan& plan);

// Fills each parameter's value, slope (first model) and the extent of the points the models put
// within tolerance (4096 Halton points of the box, held factors fixed), from res.chosen_coded.
void describe_parameters(const CampaignPlan& plan, CalibrationResult& res);

// The posterior from the models (held factors fixed), each parameter's credible interval and
// the ridge in words.
void add_posterior(const CampaignPlan& plan, CalibrationResult& res);

}  // namespace repose::calibrate
