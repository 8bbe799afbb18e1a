// One simulation as a self-contained job (case text, overrides, experiment), so that any thread
// or MPI rank can run it without the plan file, and its wire form (JSON text) for MPI.
#pragma once
#include <string>
#include <vector>

#include "calibrate/plan.h"
#include "calibrate/run_spec.h"

namespace repose::calibrate {

struct RunJob {
  RunSpec spec;
  std::string experiment;
  std::string case_path, case_text;
  std::vector<CaseOverride> overrides;
  ExperimentOptions options;
};

struct JobOutcome {
  RunRecord record;   // responses, wall time, host, rank filled in
  std::string error;  // non-empty when the simulation failed
};

RunJob make_job(const CampaignPlan& plan, const RunSpec& spec);
// Loads the case with the job's overrides and runs the experiment; never throws.
JobOutcome execute_job(const RunJob& job, int rank);

std::string job_to_text(const RunJob& job);
RunJob job_from_text(const std::string& text);
std::string outcome_to_text(const JobOutcome& outcome);
JobOutcome outcome_from_text(const std::string& text);

std::string host_name();

}  // namespace repose::calibrate
