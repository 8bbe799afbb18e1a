// A whole campaign on rank 0: every simulation of the plan (skipping those already in the
// database), the analysis, the verification at the chosen parameters, and the report.
#pragma once
#include <string>

#include "calibrate/calibration_result.h"
#include "calibrate/mpi_session.h"
#include "calibrate/plan.h"
#include "calibrate/run_source.h"

namespace repose::calibrate {

struct CampaignOptions {
  std::string db_path;  // default: OUT/campaign.sqlite
  std::string out_dir;  // default: out/calibrate/PLAN_NAME
  bool fresh = false;   // --new: replace an existing database
  int jobs = 1;         // local simulations at a time
  unsigned threads = 1; // cpu backend threads of each simulation
  bool quiet = false;
};

struct CampaignSummary {
  bool target_reached = false;
  double verification_error = 0;  // relative, of the first verified response
  int simulations = 0;
  int simulated_now = 0;          // runs this invocation ran (0 on a complete resume)
  std::string report_path;
};

// Runs `verify` (rig 0's ids) on every verified response's rig and judges each response
// (verification.h): fills res.checks and res.target_reached.
void verify_result(const CampaignPlan& plan, RunSource& source, const std::vector<RunSpec>& verify, CalibrationResult& res);

// The campaign's verdict in one line, as the headline, the report and the figures say it.
std::string verdict_line(const CampaignPlan& plan, const CalibrationResult& res);
// "sd 4.2 on 3 df (95 % interval 2.4 .. 16)" or "unknown (no replicates)".
std::string noise_text(const NoiseEstimate& noise);

CampaignSummary run_campaign(const CampaignPlan& plan, const CampaignOptions& options, MpiSession& mpi);

// The runs a plan asks for, one line each (id, seed, factor values), as `calibrate --check`
// prints them: the design's, or the adaptive loop's start and budget; then the verification.
std::string describe_planned_runs(const CampaignPlan& plan);

}  // namespace repose::calibrate
