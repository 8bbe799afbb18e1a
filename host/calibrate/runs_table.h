// The campaign's runs as CSV tables that `repose fit` reads: one row per run, the factors in
// actual values and coded (NAME_coded, as `repose design` writes them), every response the run
// measured. One file per rig (runs.csv for the campaign's case, runs_RIG.csv for another), so a
// fit never mixes two rigs' responses:
//   repose fit OUT/runs.csv --response angle --factors mu_s,mu_r --coded 0.3:0.9,0.03:0.2
#pragma once
#include <map>
#include <string>

#include "calibrate/plan.h"
#include "calibrate/run_spec.h"

namespace repose::calibrate {

// Writes the tables into `dir` (atomically); returns nothing, throws naming a file it cannot write.
void write_runs_tables(const CampaignPlan& plan, const std::map<std::string, RunRecord>& runs, const std::string& dir);

}  // namespace repose::calibrate
