// Runs a batch of campaign simulations on local worker threads and, under MPI, on the other
// ranks, and stores each result in the database the moment it arrives (rank 0 only). Runs
// already in the database are skipped, which is all that resuming a killed campaign needs.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "calibrate/mpi_session.h"
#include "calibrate/plan.h"
#include "calibrate/run_job.h"
#include "calibrate/run_store.h"

namespace repose::calibrate {

class Executor {
 public:
  // `jobs` local simulations at a time on this rank (0 allowed under MPI: rank 0 coordinates
  // only). `mpi` may be inactive. `quiet` silences the per-run progress lines.
  Executor(const CampaignPlan& plan, RunStore& store, MpiSession& mpi, int jobs, bool quiet, unsigned threads = 1);

  // Runs every spec not yet stored. When a run fails, the others in flight finish and are
  // stored, then std::runtime_error names the failed run.
  void run(const std::vector<RunSpec>& specs, const std::string& label);

  int simulated() const { return simulated_; }  // runs this process ran or received
  // Verification runs save the experiment's picture (a heap) as DIR/RUN_ID.png on the machine
  // that runs them (a shared folder under MPI on several machines).
  void set_picture_dir(const std::string& dir) { picture_dir_ = dir; }

 private:
  struct Batch;  // one run()'s jobs, shared by the local threads and the coordinating loop

  // The specs' jobs that the database does not hold yet; throws when it holds one at other
  // parameters.
  std::vector<RunJob> pending_jobs(const std::vector<RunSpec>& specs, const std::string& label) const;
  // Hands jobs to idle ranks and stores the outcomes of ranks and local threads as they come,
  // until every job handed out is back (after a failure no more are handed out).
  void coordinate(Batch& batch);
  void store_outcome(Batch& batch, JobOutcome& out);

  const CampaignPlan& plan_;
  RunStore& store_;
  MpiSession& mpi_;
  int jobs_;
  bool quiet_;
  unsigned threads_;
  int simulated_ = 0;
  std::string picture_dir_;
};

}  // namespace repose::calibrate
