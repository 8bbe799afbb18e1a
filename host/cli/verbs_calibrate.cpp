// `repose calibrate PLAN.toml`: a calibration campaign run end to end (docs/calibration.md).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <thread>

#include "calibrate/campaign.h"
#include "calibrate/mpi_session.h"
#include "calibrate/plan.h"
#include "calibrate/plan_check.h"
#include "calibrate/run_store.h"
#include "cli/cli_checks.h"
#include "cli/verbs.h"

namespace repose::cli {

namespace {

int run_calibrate(int argc, char** argv) {
  using namespace repose::calibrate;
  // Under mpirun every rank but 0 only simulates what rank 0 hands out.
  MpiSession mpi;
  if (mpi.active() && mpi.rank() != 0) {
    mpi_worker_loop(mpi.rank());
    return 0;
  }
  CLI::App app{"Run a calibration campaign: every simulation of the plan, the analysis, the verification and a report.\n"
               "Resumable: finished runs are kept in the database and never run again."};
  std::string plan_path;
  CampaignOptions options;
  int jobs = -1;
  bool check_only = false;
  app.add_option("plan", plan_path, "campaign plan (TOML, docs/calibration.md)")->required();
  app.add_option("--db", options.db_path, "campaign database (default OUT/campaign.sqlite)")
      ->check(non_empty_path());
  app.add_option("--out", options.out_dir, "folder for report.md, summary.json and the figures (default out/calibrate/NAME)")
      ->check(non_empty_path());
  app.add_flag("--new", options.fresh, "discard an existing database and start over");
  app.add_option("--jobs", jobs, "simulations at a time on this machine (default: its cores; 1 per rank under mpirun; "
                 "0 under mpirun: rank 0 only coordinates)")
      ->check(whole_number(0, 1024));
  app.add_option("--threads", options.threads,
                 "cpu backend threads of each simulation (default 1; a loop that proposes one run at a time can use them)")
      ->check(whole_number(1, 256));
  app.add_flag("--quiet", options.quiet, "no per-run progress lines");
  app.add_flag("--check", check_only,
               "load and check the plan, print the runs it asks for, their cost and the precision they can reach; run nothing");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    mpi.stop_workers();
    return parse_exit_code(app, e);
  }
  CampaignPlan plan;
  try {
    plan = load_plan(plan_path);
  } catch (const CaseError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    mpi.stop_workers();
    return 2;
  }
  if (jobs == 0 && !mpi.has_workers()) {
    mpi.stop_workers();
    return usage_error("--jobs 0 leaves no one to simulate: it is for rank 0 under mpirun with other ranks");
  }
  if (check_only) {
    std::printf("%s: plan is valid (%s mode, %zu factors, plan hash %s)\n%s", plan_path.c_str(),
                plan.mode == CampaignMode::design ? "design" : "adaptive", plan.factors.size(),
                plan_hash(canonical_plan_text(plan)).c_str(), describe_planned_runs(plan).c_str());
    mpi.stop_workers();
    try {
      const std::string out_dir = options.out_dir.empty() ? "out/calibrate/" + plan.name : options.out_dir;
      bool unreachable = false;
      std::printf("%s", describe_plan_check(plan, RunStore::read_only(options.db_path.empty() ? out_dir + "/campaign.sqlite"
                                                                                             : options.db_path, plan),
                                            1.0, unreachable)
                            .c_str());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "repose calibrate --check: %s\n", e.what());
      return 1;
    }
    return 0;
  }
  if (jobs < 0) jobs = mpi.active() ? 1 : int(std::max(1u, std::thread::hardware_concurrency()));
  options.jobs = jobs;
  try {
    CampaignSummary s = run_campaign(plan, options, mpi);
    return s.target_reached ? 0 : 3;
  } catch (const std::exception& e) {
    // Finished runs are in the database already; the other ranks are told to stop.
    mpi.stop_workers();
    std::fprintf(stderr, "repose calibrate: %s\n(every finished run is kept: run the same command again to resume)\n",
                 e.what());
    return failure_exit_code(e);
  }
}

}  // namespace

std::vector<Verb> calibrate_verbs() {
  return {{"calibrate", "calibration campaign: runs a plan's simulations (resumable, MPI), fits, verifies, reports", run_calibrate}};
}

}  // namespace repose::cli
