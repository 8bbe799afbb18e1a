#include "calibrate/campaign.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <filesystem>
#include <sstream>
#include <set>

#include "calibrate/adaptive_loop.h"
#include "calibrate/campaign_report.h"
#include "calibrate/design_export.h"
#include "calibrate/design_analysis.h"
#include "calibrate/design_runs.h"
#include "calibrate/executor.h"
#include "calibrate/report_figures.h"
#include "calibrate/run_store.h"

namespace repose::calibrate {

namespace {

std::vector<RunRecord> stored(const RunStore& store, const std::vector<RunSpec>& specs) {
  std::vector<RunRecord> out;
  for (const auto& s : specs)
    if (const RunRecord* r = store.find(s.id)) out.push_back(*r);
  return out;
}

// A designed campaign: the design runs, the fit, then verification runs at the chosen point.
void calibrate_by_design(const CampaignPlan& plan, RunStore& store, Executor& executor, CampaignRecord& record,
                         std::vector<RunSpec>& verify) {
  std::vector<RunSpec> design = design_runs(plan);
  executor.run(design, "design");
  record.result = analyse_design(plan, store);
  record.model_runs = stored(store, design);
  verify = replicate_runs(plan, "verify", record.result.chosen, 0, plan.verification_runs);
  executor.run(verify, "verify");
  add_verification(plan, stored(store, verify), design_replicate_groups(plan, store), record.result);
}

// An adaptive campaign: the loop (record.loop points at `loop`), then verification runs at its choice.
void calibrate_adaptively(const CampaignPlan& plan, RunStore& store, Executor& executor, bool quiet,
                          CampaignRecord& record, AdaptiveOutcome& loop, std::vector<RunSpec>& verify) {
  loop = run_adaptive(plan, store, executor, quiet);
  record.result = loop.result;
  record.loop = &loop;
  for (const auto& s : loop.steps) record.model_runs.push_back(s.run);
  verify = replicate_runs(plan, "verify", record.result.chosen, 1, plan.verification_runs);
  executor.run(verify, "verify");
  // The loop's run at the chosen point is replicate 0 of the verification.
  std::vector<RunRecord> at_chosen;
  for (const auto& s : loop.steps)
    if (s.run.spec.x == record.result.chosen) {
      at_chosen.push_back(s.run);
      break;
    }
  for (const auto& r : stored(store, verify)) at_chosen.push_back(r);
  add_verification(plan, at_chosen, {}, record.result);
  // The calibrated value is where the mean response meets the target; its uncertainty comes
  // from how well the surrogate knows that mean (the runs' noise averaged) and the lab's sd.
  for (auto& p : record.result.parameters) {
    const double s = std::hypot(record.result.predicted_sd, plan.measured_sd);
    p.uncertainty = std::abs(p.slope) > 0 ? s / std::abs(p.slope) : std::numeric_limits<double>::infinity();
  }
}

// How many simulations the campaign holds, their time and the host:rank pairs that ran them.
void count_simulations(CampaignRecord& record, RunStore& store, const std::vector<RunSpec>& verify) {
  std::set<std::string> hosts;
  auto count = [&](const RunRecord& r) {
    ++record.simulations;
    record.simulated_seconds += r.wall_s;
    hosts.insert(r.host + ":" + std::to_string(r.rank));
  };
  for (const auto& r : record.model_runs) count(r);
  for (const auto& r : stored(store, verify)) count(r);
  record.hosts.assign(hosts.begin(), hosts.end());
}

// The fit's figures, the loop's convergence and each verification run's own picture.
void add_figures(const CampaignPlan& plan, const std::vector<RunSpec>& verify, const std::string& out_dir,
                 CampaignRecord& record) {
  record.figures = write_figures(plan, record.result, record.model_runs, out_dir);
  if (Figure surface; write_surface_figure(plan, record.result, record.model_runs, out_dir, surface))
    record.figures.insert(record.figures.begin() + 1, surface);  // beside the contour
  write_design_expert_csv(plan, record.model_runs, out_dir + "/design_expert.csv");
  if (record.loop) record.figures.push_back(write_convergence_figure(plan, *record.loop, out_dir));
  for (const auto& s : verify)
    if (std::filesystem::exists(out_dir + "/" + s.id + ".png"))
      record.figures.push_back({s.id + ".png", "Verification run " + s.id + " (seed " + std::to_string(s.seed) +
                                                   "): the experiment's own picture."});
}

// The calibrated parameters, the loop's state and the verification, in a few lines on stdout.
void print_summary(const CampaignPlan& plan, const CampaignRecord& record, int simulated_now,
                   const std::string& report_path, const std::string& db_path) {
  const auto& res = record.result;
  std::printf("calibrate %s: %s, %d simulations (%d run now)\n", plan.name.c_str(), res.method.c_str(), record.simulations,
              simulated_now);
  for (const auto& p : res.parameters)
    if (res.target_reached)
      std::printf("  %s = %.6g +- %.3g  (target met for %.6g .. %.6g)\n", p.name.c_str(), p.value, p.uncertainty, p.set_low, p.set_high);
    else
      std::printf("  %s = %.6g  (the closest the model gets: the target is out of reach in the factor ranges)\n", p.name.c_str(), p.value);
  if (!res.target_reached)
    std::printf("  the model predicts %s = %.6g at best, the target is %.6g +- %.3g: widen the ranges or check the measured value\n",
                plan.response.c_str(), res.predicted, plan.measured, plan.absolute_tolerance());
  if (record.loop) {
    std::printf("  surrogate at the chosen point: %s = %.6g +- %.3g (run noise sd %.3g)\n", plan.response.c_str(),
                res.predicted, res.predicted_sd, res.run_noise_sd);
    if (record.loop->simulations_to_target > 0)
      std::printf("  target met after simulation %d of the loop (budget %d)\n", record.loop->simulations_to_target,
                  plan.adaptive.budget);
    else
      std::printf("  target not met within the loop's budget of %d\n", plan.adaptive.budget);
  }
  if (res.verification.empty())
    std::printf("  verification: none (verification.runs = 0): the calibrated parameters are not checked by simulation\n");
  else
    std::printf("  verification: %s = %.6g +- %.3g over %zu runs, measured %.6g, error %+.2f %%%s\n", plan.response.c_str(),
                res.verification_mean, res.verification_sd, res.verification.size(), plan.measured, 100 * res.verification_error,
                res.target_reached ? "" : " (target NOT reached)");
  std::printf("  report: %s, database: %s\n", report_path.c_str(), db_path.c_str());
}

}  // namespace

CampaignSummary run_campaign(const CampaignPlan& plan, const CampaignOptions& options, MpiSession& mpi) {
  const std::string out_dir = options.out_dir.empty() ? "out/calibrate/" + plan.name : options.out_dir;
  const std::string db_path = options.db_path.empty() ? out_dir + "/campaign.sqlite" : options.db_path;
  std::filesystem::create_directories(out_dir);
  RunStore store(db_path, plan, options.fresh);
  Executor executor(plan, store, mpi, options.jobs, options.quiet, options.threads);
  executor.set_picture_dir(out_dir);

  CampaignRecord record;
  record.plan = &plan;
  record.db_path = db_path;
  AdaptiveOutcome loop;
  std::vector<RunSpec> verify;
  if (plan.mode == CampaignMode::design)
    calibrate_by_design(plan, store, executor, record, verify);
  else
    calibrate_adaptively(plan, store, executor, options.quiet, record, loop, verify);
  mpi.stop_workers();

  count_simulations(record, store, verify);
  add_figures(plan, verify, out_dir, record);
  write_campaign_report(record, out_dir);

  CampaignSummary summary;
  summary.target_reached = record.result.target_reached;
  summary.verification_error = record.result.verification_error;
  summary.simulations = record.simulations;
  summary.simulated_now = executor.simulated();
  summary.report_path = out_dir + "/report.md";
  print_summary(plan, record, executor.simulated(), summary.report_path, db_path);
  return summary;
}

std::string describe_planned_runs(const CampaignPlan& plan) {
  std::ostringstream out;
  auto line = [&](const RunSpec& r) {
    out << "  " << r.id << "  seed " << r.seed;
    for (size_t i = 0; i < plan.factors.size(); ++i) out << "  " << plan.factors[i].name << " = " << r.x[i];
    out << "\n";
  };
  if (plan.mode == CampaignMode::design) {
    std::vector<RunSpec> design = design_runs(plan);
    out << design.size() << " design runs, in run order:\n";
    for (const auto& r : design) line(r);
  } else {
    std::vector<RunSpec> start = adaptive_start_runs(plan);
    out << start.size() << " start runs of the adaptive loop (space-filling):\n";
    for (const auto& r : start) line(r);
    out << "then up to " << plan.adaptive.budget - int(start.size())
        << " runs where the surrogate expects the largest improvement (budget " << plan.adaptive.budget << ")\n";
  }
  out << "then " << plan.verification_runs << " verification run" << (plan.verification_runs == 1 ? "" : "s")
      << " at the calibrated parameters\n";
  return out.str();
}

}  // namespace repose::calibrate
