// Simulator in the loop: a space-filling start, then one simulation at a time where a Gaussian
// process surrogate expects the largest improvement towards the measured value, until the
// surrogate's mean response at its best estimate is within the plan's tolerance of the target
// and known to within it (noise-aware: one lucky run does not stop it), or the budget is spent.
// With [adaptive] seeds = "per_run" each run packs anew and a point may be repeated. Every
// proposal depends only on the runs before it (stored by id), so a resumed or distributed loop
// proposes the same points.
#pragma once
#include <memory>
#include <vector>

#include "calibrate/calibration_result.h"
#include "calibrate/executor.h"
#include "calibrate/gaussian_process.h"
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
  int simulations_to_target = -1;  // runs after which the target was met (-1: never)
};

// One step of the loop on the runs so far (coded x, responses y): the surrogate, its best
// estimate, whether the target is met, and the next point to simulate.
struct LoopDecision {
  std::shared_ptr<GaussianProcess> gp;
  Eigen::VectorXd chosen;          // coded: argmin (mean - target)^2 + sd^2
  double mean = 0, sd = 0;         // surrogate's mean response there and its sd
  double noise_sd = 0;             // run-to-run noise (the nugget), response units
  bool met = false;                // |mean - target| <= tolerance and sd <= tolerance
  Eigen::VectorXd next;            // the next run's coded point
  bool repeat = false;             // next = chosen: a new packing where the answer is
  double expected_improvement = 0;
};
LoopDecision decide(const CampaignPlan& plan, const Eigen::MatrixXd& x, const Eigen::VectorXd& y);

// Points of the space-filling start: Halton points 1..n of the coded cube [-1, 1]^k.
std::vector<Eigen::VectorXd> halton_points(int k, int first, int count);
// The loop's space-filling start (loop-001 ...), and the packing seed of loop run `index`.
std::vector<RunSpec> adaptive_start_runs(const CampaignPlan& plan);
std::uint64_t loop_seed(const CampaignPlan& plan, int index);

AdaptiveOutcome run_adaptive(const CampaignPlan& plan, RunStore& store, Executor& executor, bool quiet);

}  // namespace repose::calibrate
