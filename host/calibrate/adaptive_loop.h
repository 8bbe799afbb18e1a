// Simulator in the loop: a space-filling start, then one simulation at a time where a Gaussian
// process surrogate expects the largest improvement towards the measured value, until a run
// meets the target within the plan's tolerance or the budget is spent. Every proposal depends
// only on the runs before it (stored by id), so a resumed or distributed loop proposes the same
// points.
#pragma once
#include <vector>

#include "calibrate/calibration_result.h"
#include "calibrate/executor.h"
#include "calibrate/plan.h"
#include "calibrate/run_store.h"

namespace repose::calibrate {

struct LoopStep {
  RunRecord run;
  double relative_error = 0;    // (y - measured) / measured
  double expected_improvement = 0;  // of the proposal that chose it (0 for the start)
};

struct AdaptiveOutcome {
  CalibrationResult result;
  std::vector<LoopStep> steps;  // in order
  int initial = 0;
  int simulations_to_target = -1;  // runs until one met the target (-1: never)
};

// Points of the space-filling start: Halton points 1..n of the coded cube [-1, 1]^k.
std::vector<Eigen::VectorXd> halton_points(int k, int first, int count);

AdaptiveOutcome run_adaptive(const CampaignPlan& plan, RunStore& store, Executor& executor, bool quiet);

}  // namespace repose::calibrate
