// The runs of a classical campaign: the plan's design (stats::Design in coded units) turned
// into simulations, centre points and replicates each with their own packing seed.
#pragma once
#include <vector>

#include "calibrate/plan.h"
#include "calibrate/run_spec.h"
#include "stats/design.h"

namespace repose::calibrate {

// The plan's design over its factors. A sweep is one factor at `levels` evenly spaced values.
// Throws stats::DesignError when the design cannot be built (e.g. a bad generator).
stats::Design build_design(const CampaignPlan& plan);

// Every design run in run order. A point is named by the first design row holding it; its
// c-th identical row (centre points) runs replicates c*R .. c*R+R-1 with R = design.replicates,
// so every replicate of a point has its own packing seed.
// For each design row, the first row with the same factor values.
std::vector<int> first_identical_rows(const stats::Design& design, int factors);

std::vector<RunSpec> design_runs(const CampaignPlan& plan);

// `count` runs at x with replicates first .. first+count-1 (verification, final replicates).
std::vector<RunSpec> replicate_runs(const CampaignPlan& plan, const std::string& phase,
                                    const std::vector<double>& x, int first, int count);

}  // namespace repose::calibrate
