// The classical chain on a finished design: a response surface (stats::analyse, optional
// backward reduction) or, for a one-factor sweep, a calibration curve; then the parameters
// that hit the measured value, the set of equally good ones, and each parameter's uncertainty.
#pragma once
#include "calibrate/calibration_result.h"
#include "calibrate/plan.h"
#include "calibrate/run_store.h"

namespace repose::calibrate {

// Throws when a design run is missing from the store or the model cannot be fitted.
CalibrationResult analyse_design(const CampaignPlan& plan, const RunStore& store);

// After the verification runs: their mean, sd, relative error, and the uncertainties with the
// replicate noise of the design and the verification pooled.
void add_verification(const CampaignPlan& plan, const std::vector<RunRecord>& runs,
                      const std::vector<std::vector<double>>& other_replicate_groups, CalibrationResult& result);

// The design's responses grouped by design point (centre replicates, repeated points).
std::vector<std::vector<double>> design_replicate_groups(const CampaignPlan& plan, const RunStore& store);

}  // namespace repose::calibrate
