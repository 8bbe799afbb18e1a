#include "calibrate/plan_check.h"

#include <ctime>
#include <cmath>
#include <sstream>

#include "calibrate/adaptive_loop.h"
#include "calibrate/design_runs.h"
#include "calibrate/noise.h"
#include "calibrate/observations.h"
#include "engine/backend_factory.h"
#include "engine/simulation.h"
#include "experiments/repose.h"
#include "util/number_text.h"

namespace repose::calibrate {

namespace {

// The simulated time a run on this case takes, at most: a heap settles about a second after its
// lifted wall stops (sooner when it ends once the wall is clear); other experiments run to their
// max_time at most; a case without one to its end_time.
double longest_run(const CaseSpec& spec, std::string& why) {
  const ExperimentSpec& ex = spec.experiment;
  if (ex.type.empty()) {
    why = "end_time";
    return spec.time.end_time;
  }
  if (ex.type == "repose") {
    const ReposeSettings& heap = settings_of<ReposeSettings>(ex);
    double lift_end = heap.lift_end;
    for (const auto& w : spec.walls)
      if (lift_end <= 0 && w.name == heap.lift_wall) lift_end = w.motion.stop_time;
    if (lift_end > 0 && lift_end + 1 < ex.max_time) {
      why = heap.end_when_clear ? "the lift's end + 1 s; runs that end once the wall is clear are shorter" : "the lift's end + 1 s";
      return lift_end + 1;
    }
  }
  why = "max_time; most runs end sooner";
  return ex.max_time;
}

// Times steps of the case at the factors' centre on one cpu thread for about `seconds`.
double probe_cost(const CampaignPlan& plan, int rig, double seconds, std::string& how) {
  const PlanRig& r = plan.rigs[size_t(rig)];
  const std::vector<double> centre = to_actual(plan, Eigen::VectorXd::Zero(int(plan.factors.size())));
  CaseSpec spec = load_case_from_string(r.case_text, r.case_path, run_overrides(plan, rig, centre, plan.base_seed));
  Model model = build_model(spec);
  Simulation sim(model, make_backend("cpu", -1, 1, gpu::kDefaultWorkgroup), KernelVariant::fastest_for("cpu", model), 50);
  sim.advance(10);  // lists built, caches warm
  // Processor time, not wall time: the estimate should not depend on what else the machine runs.
  const std::clock_t start = std::clock();
  uint64_t steps = 0;
  double elapsed = 0;
  do {
    sim.advance(50);
    steps += 50;
    elapsed = double(std::clock() - start) / CLOCKS_PER_SEC;
  } while (elapsed < seconds && steps < 200000);
  const double particles = std::max<double>(1, model.n_particles);
  const double per_particle_step = elapsed / (double(steps) * particles);
  std::string why;
  const double duration = longest_run(spec, why);
  const double total_steps = std::ceil(duration / model.dt);
  std::ostringstream s;
  s << "probe: " << model.n_particles << " particles x " << format_g(total_steps, 4) << " steps (" << format_g(duration, 4)
    << " s, " << why << ", at dt " << format_g(model.dt, 3) << " s) x " << format_g(per_particle_step * 1e9, 3)
    << " ns of processor time per particle-step, over the first " << steps << " steps: an estimate";
  how = s.str();
  return per_particle_step * particles * total_steps;
}

std::string duration_text(double s) {
  char buf[64];
  if (s < 10) std::snprintf(buf, sizeof buf, "%.2g s", s);
  else if (s < 120) std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 7200) std::snprintf(buf, sizeof buf, "%.1f min", s / 60);
  else std::snprintf(buf, sizeof buf, "%.1f h", s / 3600);
  return buf;
}

// The noise of a response: the replicates already stored, else the plan's noise_sd guess.
double known_noise(const CampaignPlan& plan, int response, const std::map<std::string, RunRecord>& stored, std::string& source) {
  const PlanResponse& r = plan.responses[size_t(response)];
  Observations obs;
  std::vector<const RunRecord*> runs;
  for (const auto& [id, run] : stored)
    if (run.spec.rig == r.rig && run.responses.count(r.name)) runs.push_back(&run);
  obs.x.resize(int(runs.size()), int(plan.factors.size()));
  obs.y.resize(int(runs.size()));
  for (size_t i = 0; i < runs.size(); ++i) {
    obs.x.row(int(i)) = to_coded(plan, runs[i]->spec.x).transpose();
    obs.y[int(i)] = runs[i]->responses.at(r.name);
  }
  const NoiseEstimate n = pooled_noise(replicate_groups(obs));
  if (n.known()) {
    source = "measured from the stored replicates, " + std::to_string(n.df) + " df";
    return n.sd;
  }
  if (r.noise_sd > 0) {
    source = "the plan's noise_sd";
    return r.noise_sd;
  }
  return -1;
}

}  // namespace

std::map<int, int> planned_runs_per_rig(const CampaignPlan& plan) {
  std::map<int, int> runs;
  const int model_runs = plan.mode == CampaignMode::design ? int(design_runs(plan).size())
                                                           : int(pilot_runs(plan).size()) + plan.adaptive.budget;
  for (int rig : plan.rigs_of(plan.calibration_responses())) runs[rig] += model_runs;
  for (int rig : plan.rigs_of(plan.verified_responses())) runs[rig] += plan.verification_runs;
  return runs;
}

double run_cost(const CampaignPlan& plan, int rig, const std::map<std::string, RunRecord>& stored, double probe_seconds,
                std::string& how) {
  double sum = 0;
  int n = 0;
  for (const auto& [id, r] : stored)
    if (r.spec.rig == rig) sum += r.wall_s, ++n;
  if (n > 0) {
    how = "the mean of " + std::to_string(n) + " stored runs";
    return sum / n;
  }
  return probe_cost(plan, rig, probe_seconds, how);
}

std::string precision_text(const CampaignPlan& plan, const std::map<std::string, RunRecord>& stored, bool& unreachable) {
  std::ostringstream out;
  const int nv = plan.verification_runs;
  for (int v : plan.verified_responses()) {
    const PlanResponse& r = plan.responses[size_t(v)];
    const double tol = r.absolute_tolerance(), se_m = r.measured_se();
    out << "precision of " << r.label << " (tolerance " << format_g(tol, 4) << ", lab standard error " << format_g(se_m, 4) << "):\n";
    if (se_m >= tol) {
      unreachable = true;
      out << "  UNREACHABLE: the lab's own standard error exceeds the tolerance; no number of runs can confirm it "
             "(widen the tolerance or give the lab's replicate count, measured_n)\n";
      continue;
    }
    if (nv == 0) {
      unreachable = true;
      out << "  UNREACHABLE: verification.runs = 0 verifies nothing (the campaign ends with 'nothing verified')\n";
      continue;
    }
    const double limit = std::sqrt(nv * (tol * tol - se_m * se_m));
    std::string source;
    const double sd = known_noise(plan, v, stored, source);
    if (sd < 0) {
      out << "  noise unknown until replicates run (" << (plan.mode == CampaignMode::adaptive ? "the pilot" : "centre points")
          << "; give noise_sd from an earlier pilot to check now): " << nv << " verification runs confirm the tolerance only if "
          << "the run-to-run sd is below " << format_g(limit, 3) << "\n";
      continue;
    }
    const double se_d = std::sqrt(sd * sd / nv + se_m * se_m);
    const int needed = runs_for_standard_error(sd, std::sqrt(tol * tol - se_m * se_m));
    out << "  run-to-run sd " << format_g(sd, 3) << " (" << source << "): " << nv << " verification runs give a standard error of "
        << format_g(se_d, 3) << " on the difference; " << needed << " would reach the tolerance\n";
    if (se_d > tol) {
      unreachable = true;
      out << "  UNREACHABLE with verification.runs = " << nv << ": raise it to " << needed << " or widen the tolerance to "
          << format_g(100 * (se_d / std::abs(r.measured)), 3) << " %\n";
    }
    if (plan.mode == CampaignMode::adaptive && r.role == ResponseRole::calibrate) {
      const double best = sd / std::sqrt(double(plan.adaptive.budget + int(pilot_runs(plan).size())));
      if (best > tol) {
        unreachable = true;
        out << "  UNREACHABLE for the loop: even with every run of its budget at the answer the surrogate knows the mean only to "
            << format_g(best, 3) << "; its stop rule needs about " << needed << " runs there\n";
      }
    }
  }
  return out.str();
}

std::string describe_plan_check(const CampaignPlan& plan, const std::map<std::string, RunRecord>& stored, double probe_seconds,
                                bool& unreachable) {
  std::ostringstream out;
  double total_runs = 0, total_seconds = 0;
  std::ostringstream rigs;
  for (auto [rig, runs] : planned_runs_per_rig(plan)) {
    std::string how;
    const double cost = run_cost(plan, rig, stored, probe_seconds, how);
    total_runs += runs;
    total_seconds += runs * cost;
    rigs << "  " << (rig == 0 ? std::string("campaign case") : "rig " + plan.rigs[size_t(rig)].name) << ": " << runs
         << " runs x " << duration_text(cost) << " (" << how << ")\n";
  }
  out << "cost: at most " << total_runs << " simulations, about " << duration_text(total_seconds)
      << " of CPU time on one thread each (divide by --jobs, or spread over mpirun ranks)\n"
      << rigs.str();
  if (plan.mode == CampaignMode::adaptive && plan.adaptive.seed_per_run && plan.verification_runs > 0)
    out << "  and " << plan.verification_runs
        << " more for each verification the loop runs before its budget is spent and that does not confirm it\n";
  out << precision_text(plan, stored, unreachable);
  return out.str();
}

}  // namespace repose::calibrate
