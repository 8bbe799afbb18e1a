// Simulator in the loop: a noise pilot (replicate fills at one or two points), a space-filling
// start, then one simulation at a time where Gaussian-process surrogates (one per calibrating
// response, the noise held inside the pilot's confidence interval) expect the largest
// improvement towards the measured values, until the surrogates' means at their best estimate
// are within every tolerance and known to within it (noise-aware: one lucky run does not stop
// it), or the budget is spent. When the surrogate meets the tolerance before the budget is
// spent, the verification runs there and then: confirmed, the loop ends; otherwise its runs join
// the surrogate's data and the loop goes on (a surrogate sure of a wrong mean does not end it). With [adaptive] seeds = "per_run" each run packs anew and a point
// may be repeated. Every proposal depends only on the runs before it (stored by id), so a
// resumed, distributed or budget-raised loop proposes the same points.
#pragma once
#include <memory>
#include <vector>

#include "calibrate/calibration_result.h"
#include "calibrate/gaussian_process.h"
#include "calibrate/observations.h"
#include "calibrate/plan.h"
#include "calibrate/run_source.h"

namespace repose::calibrate {

struct LoopStep {
  RunRecord run;                  // on rig 0's id (the point); values per calibrating response below
  std::vector<double> values;     // per calibrating response
  double relative_error = 0;      // of the first calibrating response: (y - measured) / measured
  double expected_improvement = 0;  // of the proposal that chose it (0 for the start)
};

// A verification the loop ran before its budget was spent, because its surrogate met the
// tolerance, and that did not confirm it: its runs then joined the surrogate's data.
struct VerificationRound {
  int loop_runs = 0;                 // the loop's length when it ran (its ids: verify-NNN-rK)
  std::vector<RunSpec> runs;         // rig 0's ids, at the point the surrogate chose then
  std::vector<ResponseCheck> checks; // why the loop went on
  bool budget_end = false;           // a smaller budget ended here (resumed past), not the tolerance met
};

struct AdaptiveOutcome {
  CalibrationResult result;
  std::vector<VerificationRound> rounds;  // unconfirmed verifications fed back, in order
  std::vector<LoopStep> steps;     // in order
  std::vector<RunRecord> pilot;    // the noise pilot's runs (first calibrating response's rig)
  int initial = 0;
  int simulations_to_target = -1;  // loop runs after which the target was met (-1: never)
};

// One step of the loop on the runs so far: the surrogates, their best estimate, whether the
// target is met, and the next point to simulate.
struct LoopDecision {
  std::vector<ResponseModel> models;  // one per calibrating response (a Gaussian process each)
  std::vector<std::shared_ptr<GaussianProcess>> gps;
  Eigen::VectorXd chosen;          // coded: argmin of the expected miss (calibration_result.h)
  bool met = false;                // every |mean - target| <= tolerance and sd <= tolerance
  Eigen::VectorXd next;            // the next run's coded point
  bool repeat = false;             // next = chosen: a new packing where the answer is
  double expected_improvement = 0; // of the proposal (one response: EI; several: probability all land in tolerance)
};
// `noise`: each calibrating response's noise from the replicates among `observations` (known
// noise bounds the surrogate's nugget to its 95 % interval).
LoopDecision decide(const CampaignPlan& plan, const std::vector<Observations>& observations,
                    const std::vector<NoiseEstimate>& noise);

// Points of the space-filling start: Halton points 1..n of the coded cube [-1, 1]^k.
std::vector<Eigen::VectorXd> halton_points(int k, int first, int count);
// The loop's space-filling start (loop-001 ...), its pilot (pilot-P-rR), and the packing seed of
// loop run `index`. Ids are rig 0's: on_rigs() gives each calibrating rig's.
std::vector<RunSpec> adaptive_start_runs(const CampaignPlan& plan);
std::vector<RunSpec> pilot_runs(const CampaignPlan& plan);
std::uint64_t loop_seed(const CampaignPlan& plan, int index);
// The verification runs of a loop that ended after `loop_runs` runs: at the chosen point, each
// its own seed, named after the loop's length (a raised budget verifies its own answer anew).
// `round`: how many unconfirmed verifications were fed back before it; after one, the packings
// are new (base + 900000 + 1000 round + r), so a verification never repeats a packing the
// surrogate has learned from.
std::vector<RunSpec> adaptive_verification_runs(const CampaignPlan& plan, const std::vector<double>& x, int loop_runs,
                                                int round = 0);

AdaptiveOutcome run_adaptive(const CampaignPlan& plan, RunSource& source, bool quiet);

}  // namespace repose::calibrate
