#include "calibrate/campaign.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <set>
#include <sstream>

#include "calibrate/adaptive_loop.h"
#include "calibrate/campaign_report.h"
#include "calibrate/design_export.h"
#include "calibrate/design_analysis.h"
#include "calibrate/design_runs.h"
#include "calibrate/executor.h"
#include "calibrate/observations.h"
#include "calibrate/plan_check.h"
#include "calibrate/report_figures.h"
#include "calibrate/run_store.h"
#include "calibrate/runs_table.h"
#include "io/output_dir.h"

namespace repose::calibrate {

namespace {

// The campaign's runs: simulated by the executor, kept in the database.
class ExecutedRuns : public RunSource {
 public:
  ExecutedRuns(Executor& executor, RunStore& store) : executor_(executor), store_(store) {}
  void run(const std::vector<RunSpec>& specs, const std::string& label) override { executor_.run(specs, label); }
  const RunRecord* find(const std::string& id) const override { return store_.find(id); }
  std::string where() const override { return store_.path(); }

 private:
  Executor& executor_;
  RunStore& store_;
};

// Groups of runs at identical parameters among `runs` (a response's replicates).
NoiseEstimate noise_among(const std::vector<RunRecord>& runs, const std::string& response) {
  Observations obs;
  obs.x.resize(int(runs.size()), runs.empty() ? 0 : int(runs[0].spec.x.size()));
  obs.y.resize(int(runs.size()));
  for (size_t i = 0; i < runs.size(); ++i) {
    for (size_t j = 0; j < runs[i].spec.x.size(); ++j) obs.x(int(i), int(j)) = runs[i].spec.x[j];
    obs.y[int(i)] = response_value(runs[i], response);
  }
  return pooled_noise(replicate_groups(obs));
}

}  // namespace

void verify_result(const CampaignPlan& plan, RunSource& source, const std::vector<RunSpec>& verify, CalibrationResult& res) {
  const std::vector<int> verified = plan.verified_responses();
  res.checks.clear();
  res.target_reached = false;
  if (verify.empty()) return;  // nothing verified: the target cannot be reached
  source.run(on_rigs(plan, verify, plan.rigs_of(verified)), "verify");
  for (int v : verified) {
    const PlanResponse& r = plan.responses[size_t(v)];
    std::vector<RunRecord> runs;
    for (const auto& s : verify) {
      const std::string id = rig_run_id(plan, s.id, r.rig);
      const RunRecord* run = source.find(id);
      if (!run) throw std::runtime_error(id + " is missing from " + source.where());
      runs.push_back(*run);
    }
    // The response's noise: its calibration replicates (when it calibrates) and the verification runs.
    NoiseEstimate noise = noise_among(runs, r.name);
    for (const auto& m : res.models)
      if (m.response == v) noise = combine(m.noise, noise);
    res.checks.push_back(check_response(plan, v, runs, noise));
  }
  res.target_reached = !res.checks.empty();
  for (const auto& c : res.checks) res.target_reached = res.target_reached && c.agreement == Agreement::confirmed;
}

namespace {

// A designed campaign: the design runs, the analysis, then verification runs at the chosen point.
void calibrate_by_design(const CampaignPlan& plan, RunSource& source, CampaignRecord& record, std::vector<RunSpec>& verify) {
  source.run(on_rigs(plan, design_runs(plan), plan.rigs_of(plan.calibration_responses())), "design");
  record.result = analyse_design(plan, source);
  verify = replicate_runs(plan, "verify", record.result.chosen, 0, plan.verification_runs);
  verify_result(plan, source, verify, record.result);
}

// An adaptive campaign: the pilot and the loop (record.loop points at `loop`), then verification
// runs at its choice.
void calibrate_adaptively(const CampaignPlan& plan, RunSource& source, bool quiet, CampaignRecord& record,
                          AdaptiveOutcome& loop, std::vector<RunSpec>& verify) {
  loop = run_adaptive(plan, source, quiet);
  record.result = loop.result;
  record.loop = &loop;
  verify = adaptive_verification_runs(plan, record.result.chosen, int(loop.steps.size()), int(loop.rounds.size()));
  verify_result(plan, source, verify, record.result);
}

// How many simulations the database holds, their time and the host:rank pairs that ran them.
void count_simulations(CampaignRecord& record, const RunStore& store) {
  std::set<std::string> hosts;
  for (const auto& [id, r] : store.runs()) {
    ++record.simulations;
    record.simulated_seconds += r.wall_s;
    hosts.insert(r.host + ":" + std::to_string(r.rank));
  }
  record.hosts.assign(hosts.begin(), hosts.end());
}

// The fit's figures, the loop's convergence and each verification run's own picture.
void add_figures(const CampaignPlan& plan, const std::vector<RunSpec>& verify, const std::string& out_dir,
                 CampaignRecord& record) {
  record.figures = write_figures(plan, record.result, out_dir);
  // The first calibrating response's runs (a path fits no model: nothing for Design-Expert then).
  if (!record.result.models.empty() && record.result.path.empty()) {  // a path's "model" joins its means
    const ResponseModel& model = record.result.models.front();
    if (Figure surface; write_surface_figure(plan, record.result, model, out_dir, surface))
      record.figures.insert(record.figures.begin() + 1, surface);  // beside the contour
    write_design_expert_csv(plan, model, out_dir + "/design_expert.csv");
  }
  if (record.loop) record.figures.push_back(write_convergence_figure(plan, *record.loop, out_dir));
  for (const auto& s : on_rigs(plan, verify, plan.rigs_of(plan.verified_responses())))
    if (std::filesystem::exists(out_dir + "/" + s.id + ".png"))
      record.figures.push_back({s.id + ".png", "Verification run " + s.id + " (seed " + std::to_string(s.seed) +
                                                   "): the experiment's own picture."});
}

std::string interval_text(const ParameterEstimate& p) {
  char buf[160];
  if (!p.has_posterior) return "";
  std::snprintf(buf, sizeof buf, "; 90 %% credible %.4g .. %.4g%s", p.low, p.high,
                p.identified ? "" : " (not identified by the data)");
  return buf;
}

// The headline: the verdict first, then the parameters, the noise and each verification check.
void print_summary(const CampaignPlan& plan, const CampaignRecord& record, int simulated_now, const std::string& report_path,
                   const std::string& db_path) {
  const auto& res = record.result;
  std::printf("calibrate %s: %s, %d simulations (%d run now)\n", plan.name.c_str(), res.method.c_str(), record.simulations,
              simulated_now);
  std::printf("  %s\n", verdict_line(plan, res).c_str());
  if (!res.model_on_target && plan.mode == CampaignMode::design)
    std::printf("  the model does not reach the measured value within the tolerance anywhere in the factor box: the closest it "
                "gets is below; widen the ranges or check the measured value\n");
  for (const auto& p : res.parameters)
    std::printf("  %s = %.6g%s  (model within tolerance for %.6g .. %.6g)\n", p.name.c_str(), p.value, interval_text(p).c_str(),
                p.set_low, p.set_high);
  if (!res.ridge_text.empty()) std::printf("  %s\n", res.ridge_text.c_str());
  for (const auto& m : res.models) {
    const PlanResponse& r = plan.responses[size_t(m.response)];
    std::printf("  model at the chosen point: %s = %.6g +- %.3g; run-to-run noise %s\n", r.label.c_str(), m.predicted,
                m.predicted_sd, noise_text(m.noise).c_str());
  }
  if (record.loop) {
    if (record.loop->simulations_to_target > 0)
      std::printf("  the loop's surrogate met the tolerance after loop run %d (budget %d)\n", record.loop->simulations_to_target,
                  plan.adaptive.budget);
    else
      std::printf("  the loop's surrogate did not meet the tolerance within its budget of %d\n", plan.adaptive.budget);
  }
  for (const auto& c : res.checks) std::printf("  verification %s\n", check_text(plan, c).c_str());
  std::printf("  report: %s, runs: %s, database: %s\n", report_path.c_str(),
              (std::filesystem::path(report_path).parent_path() / "runs.csv").string().c_str(), db_path.c_str());
}

}  // namespace

std::string verdict_line(const CampaignPlan& plan, const CalibrationResult& res) {
  if (res.target_reached) return "TARGET REACHED: the verification agrees with the measured value within the tolerance";
  if (res.checks.empty()) return "target NOT reached: nothing verified (verification.runs = 0)";
  bool contradicted = false;
  for (const auto& c : res.checks) contradicted = contradicted || c.agreement == Agreement::contradicted;
  (void)plan;
  return contradicted ? "target NOT reached: the verification contradicts the calibration (it misses the tolerance)"
                      : "target NOT reached: the verification cannot confirm the tolerance (too few runs for the noise, or the "
                        "lab's uncertainty)";
}

std::string noise_text(const NoiseEstimate& n) {
  if (!n.known()) return "unknown (no replicates)";
  char buf[160];
  std::snprintf(buf, sizeof buf, "sd %.4g on %d df (95 %% interval %.4g .. %.4g)", n.sd, n.df, n.low, n.high);
  return buf;
}

CampaignSummary run_campaign(const CampaignPlan& plan, const CampaignOptions& options, MpiSession& mpi) {
  const std::string out_dir = options.out_dir.empty() ? "out/calibrate/" + plan.name : options.out_dir;
  const std::string db_path = options.db_path.empty() ? out_dir + "/campaign.sqlite" : options.db_path;
  OutputFolder folder(out_dir);  // two campaigns never write one folder (each its report and figures)
  folder.remove_leftovers();     // what a killed campaign left half-written
  RunStore store(db_path, plan, options.fresh);
  Executor executor(plan, store, mpi, options.jobs, options.quiet, options.threads);
  executor.set_picture_dir(out_dir);
  ExecutedRuns source(executor, store);
  if (!options.quiet) {
    bool unreachable = false;
    const std::string precision = precision_text(plan, store.runs(), unreachable);
    if (unreachable) std::fprintf(stderr, "calibrate %s: before running:\n%s", plan.name.c_str(), precision.c_str());
  }

  CampaignRecord record;
  record.plan = &plan;
  record.db_path = db_path;
  AdaptiveOutcome loop;
  std::vector<RunSpec> verify;
  if (plan.mode == CampaignMode::design)
    calibrate_by_design(plan, source, record, verify);
  else
    calibrate_adaptively(plan, source, options.quiet, record, loop, verify);
  mpi.stop_workers();

  count_simulations(record, store);
  add_figures(plan, verify, out_dir, record);
  write_runs_tables(plan, store.runs(), out_dir);
  write_campaign_report(record, out_dir);

  CampaignSummary summary;
  summary.target_reached = record.result.target_reached;
  if (!record.result.checks.empty())
    summary.verification_error = record.result.checks[0].relative_error(plan.responses[size_t(record.result.checks[0].response)].measured);
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
  const std::vector<int> rigs = plan.rigs_of(plan.calibration_responses());
  std::string on = "";
  if (rigs.size() > 1 || rigs[0] != 0) {
    on = ", each on rig";
    for (int r : rigs) on += " " + (r == 0 ? std::string("(the campaign's case)") : plan.rigs[size_t(r)].name);
  }
  if (plan.mode == CampaignMode::design) {
    std::vector<RunSpec> design = design_runs(plan);
    out << design.size() << " design runs" << on << ", in run order:\n";
    for (const auto& r : design) line(r);
  } else {
    std::vector<RunSpec> pilot = pilot_runs(plan);
    if (!pilot.empty()) out << pilot.size() << " noise pilot runs" << on << " (replicates, each its own seed):\n";
    for (const auto& r : pilot) line(r);
    std::vector<RunSpec> start = adaptive_start_runs(plan);
    out << start.size() << " start runs of the adaptive loop" << on << " (space-filling):\n";
    for (const auto& r : start) line(r);
    out << "then up to " << plan.adaptive.budget - int(start.size())
        << " runs where the surrogate expects the largest improvement (budget " << plan.adaptive.budget << ")\n";
  }
  std::string where;
  for (int r : plan.rigs_of(plan.verified_responses()))
    where += (where.empty() ? " on " : ", ") + (r == 0 ? std::string("the campaign's case") : "rig " + plan.rigs[size_t(r)].name);
  out << "then " << plan.verification_runs << " verification run" << (plan.verification_runs == 1 ? "" : "s") << where
      << " at the calibrated parameters\n";
  return out.str();
}

}  // namespace repose::calibrate
