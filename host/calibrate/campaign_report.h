// The campaign's written results: report.md (Markdown with the figures), summary.json (the
// numbers for scripts), both written atomically into the output folder.
#pragma once
#include <string>
#include <vector>

#include "calibrate/adaptive_loop.h"
#include "calibrate/calibration_result.h"
#include "calibrate/plan.h"
#include "calibrate/report_figures.h"

namespace repose::calibrate {

struct CampaignRecord {
  const CampaignPlan* plan = nullptr;
  std::string db_path;
  CalibrationResult result;
  const AdaptiveOutcome* loop = nullptr;  // adaptive mode only
  std::vector<Figure> figures;
  int simulations = 0;                    // runs in the database
  double simulated_seconds = 0;           // their summed wall time
  std::vector<std::string> hosts;         // "host:rank" that ran them
};

void write_campaign_report(const CampaignRecord& record, const std::string& dir);

}  // namespace repose::calibrate
