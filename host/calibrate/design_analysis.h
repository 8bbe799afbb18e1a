// The classical chain on a finished design: per calibrating response a response surface
// (stats::analyse, optional backward reduction) or, for a one-factor sweep, a calibration curve;
// then the parameters that hit the measured values (factors in design.fix held), the set of
// equally good ones and the posterior. A steepest-ascent path fits no model: its best point is
// chosen from the means of its replicates.
#pragma once
#include "calibrate/calibration_result.h"
#include "calibrate/plan.h"
#include "calibrate/run_source.h"

namespace repose::calibrate {

// Throws when a design run is missing from the source or a model cannot be fitted.
CalibrationResult analyse_design(const CampaignPlan& plan, const RunSource& source);

// The design's replicate groups of a response (centre points, repeated points, path replicates).
std::vector<std::vector<double>> design_replicate_groups(const CampaignPlan& plan, const RunSource& source, int response);

}  // namespace repose::calibrate
