// The PNG figures of a campaign report: response-surface contours, main effects, one
// calibration curve per factor (through the chosen point), predicted vs simulated, the
// verification runs against the measured value, and the adaptive loop's convergence.
#pragma once
#include <string>
#include <vector>

#include "calibrate/adaptive_loop.h"
#include "calibrate/calibration_result.h"
#include "calibrate/plan.h"

namespace repose::calibrate {

struct Figure {
  std::string file;     // name inside the output folder
  std::string caption;
};

// `runs`: the runs the model was fitted to. Writes into `dir`; returns what it wrote.
std::vector<Figure> write_figures(const CampaignPlan& plan, const CalibrationResult& result,
                                  const std::vector<RunRecord>& runs, const std::string& dir);

Figure write_convergence_figure(const CampaignPlan& plan, const AdaptiveOutcome& loop, const std::string& dir);

}  // namespace repose::calibrate
