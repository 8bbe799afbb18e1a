// One response's runs as the statistics see them: coded points and values, each run on the rig
// of the response. A campaign's points are named once (rig 0's ids) and run on every rig it
// needs: "loop-004" on the box, "loop-004@cylinder" on the cylinder.
#pragma once
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "calibrate/plan.h"
#include "calibrate/run_source.h"

namespace repose::calibrate {

// The id of a point's run on `rig`: the point's id, with "@NAME" for rig r > 0.
std::string rig_run_id(const CampaignPlan& plan, const std::string& id, int rig);
// Each spec once per rig (in rig order within a spec).
std::vector<RunSpec> on_rigs(const CampaignPlan& plan, const std::vector<RunSpec>& points, const std::vector<int>& rigs);

struct Observations {
  int response = 0;           // index into plan.responses
  Eigen::MatrixXd x;          // coded points, one row per run
  Eigen::VectorXd y;
  std::vector<RunRecord> runs;
};

// A run's value of a response; throws naming the run when it has none.
double response_value(const RunRecord& run, const std::string& name);

// Response `response` at the runs of `points` (each on the response's rig). Throws naming a run
// the source does not hold.
Observations observe(const CampaignPlan& plan, const RunSource& source, const std::vector<RunSpec>& points, int response);

// The values of runs at identical points (replicates), one group per point.
std::vector<std::vector<double>> replicate_groups(const Observations& obs);

}  // namespace repose::calibrate
