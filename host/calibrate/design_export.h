// What a campaign hands to Design-Expert users: its runs as a CSV Design-Expert imports (its own
// column layout: Std, Run, "Factor 1 A:name (unit)", ..., "Response 1 name (unit)", actual
// values), and a 3D picture of the fitted response surface beside the report's contour.
#pragma once
#include <string>
#include <vector>

#include "calibrate/calibration_result.h"
#include "calibrate/plan.h"
#include "calibrate/report_figures.h"

namespace repose::calibrate {

// A calibrating response's runs in the order they appear (standard order: the design point + 1), every response the
// experiment reported after the plan's own.
void write_design_expert_csv(const CampaignPlan& plan, const ResponseModel& model, const std::string& path);

// surface_3d.png over the first two factors (the others at their calibrated values), the runs as
// dots; with fewer than two factors, nothing (returns false).
bool write_surface_figure(const CampaignPlan& plan, const CalibrationResult& result, const ResponseModel& model,
                          const std::string& dir, Figure& figure);

}  // namespace repose::calibrate
