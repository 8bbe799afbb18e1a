// What `repose calibrate --check` says before anything runs: the plan's cost (simulations, and
// CPU time per run from the campaign's own stored runs or a short timed probe of each rig's case:
// particles x steps x the measured cost of a particle-step), and the precision the budget can
// reach at the run-to-run noise (the plan's noise_sd, or the replicates already stored). A
// tolerance the budget cannot reach is flagged as UNREACHABLE, with what would reach it.
#pragma once
#include <map>
#include <string>

#include "calibrate/plan.h"
#include "calibrate/run_spec.h"

namespace repose::calibrate {

// The most simulations the plan asks for on each rig (design or pilot + budget, verification).
std::map<int, int> planned_runs_per_rig(const CampaignPlan& plan);

// CPU seconds of one run on `rig`: the mean wall time of its stored runs, or a probe of at most
// about `probe_seconds`; `how` says which, with the numbers. Throws when the case cannot be built.
double run_cost(const CampaignPlan& plan, int rig, const std::map<std::string, RunRecord>& stored, double probe_seconds,
                std::string& how);

// Lines on the precision each response can reach; `unreachable` is set when one cannot.
std::string precision_text(const CampaignPlan& plan, const std::map<std::string, RunRecord>& stored, bool& unreachable);

// The whole --check report after the list of runs: cost, then precision.
std::string describe_plan_check(const CampaignPlan& plan, const std::map<std::string, RunRecord>& stored, double probe_seconds,
                                bool& unreachable);

}  // namespace repose::calibrate
