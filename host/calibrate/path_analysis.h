// A steepest-ascent path (the cabbage study's Table 8): points on a line through the factor box,
// each run `replicates` times with its own packing seeds; no model is fitted. The chosen point is
// the one whose means lie nearest the measured values (each in its response's scale); the
// report gives every point's mean with its standard error, and the range a central composite
// design around the chosen point would take (its neighbours on the path as -1 and +1).
#pragma once
#include <vector>

#include "calibrate/calibration_result.h"
#include "calibrate/observations.h"

namespace repose::calibrate {

CalibrationResult analyse_path(const CampaignPlan& plan, const std::vector<Observations>& observations);

}  // namespace repose::calibrate
