// The PNG figures of a campaign report: response-surface contours, main effects, one
// calibration curve per factor (through the chosen point), predicted vs simulated, the posterior
// with its 90 % region and ridge, a steepest-ascent path, the verification runs against the
// measured value, and the adaptive loop's convergence. Each chart's legend names every series it
// draws with the mark it is drawn with.
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

// "e", "G (Pa)": a factor's name with the unit of its case key.
std::string factor_label(const PlanFactor& f);

// Writes into `dir`; returns what it wrote.
std::vector<Figure> write_figures(const CampaignPlan& plan, const CalibrationResult& result, const std::string& dir);

Figure write_convergence_figure(const CampaignPlan& plan, const AdaptiveOutcome& loop, const std::string& dir);

// The posterior: posterior.png (the two first free factors' marginal with its 90 % region, the
// ridge, the runs and the chosen point; one free factor: its marginal density). posterior_figures.cpp.
std::vector<Figure> posterior_figures(const CampaignPlan& plan, const CalibrationResult& result, const std::string& dir);

}  // namespace repose::calibrate
