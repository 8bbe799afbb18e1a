#include "io/case_run.h"

#include <chrono>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "case/case_loader.h"
#include "engine/backend_factory.h"
#include "engine/escape_check.h"
#include "engine/memory_need.h"
#include "engine/model.h"
#include "engine/simulation.h"
#include "io/output_dir.h"
#include "io/provenance.h"
#include "io/restart_state.h"
#include "io/run_output.h"
#include "io/run_summary.h"
#include "io/state_file.h"
#include "util/input_error.h"
#include "util/number_text.h"
#include "util/progress.h"
#include "util/stop_signal.h"

namespace repose {

namespace {

namespace fs = std::filesystem;

// More steps than this cannot be meant (years of computing); the limit also keeps step counts
// exact in a double.
constexpr double kMostSteps = 1e12;

uint64_t steps_of(double seconds, double dt, const char* what) {
  double steps = std::round(seconds / dt);
  if (!(steps <= kMostSteps))
    throw BadInput(std::string(what) + ": " + format_g(seconds, 6) + " s is " + format_g(steps, 4) + " steps of " +
                   format_g(dt, 4) + " s: more than 1e12 steps cannot be meant");
  return uint64_t(steps);
}

// The step to stop at: --steps or --time more, or the case's end time.
uint64_t target_step(const CaseRunOptions& o, const Model& m, uint64_t start) {
  if (o.steps) {
    if (double(*o.steps) > kMostSteps) throw BadInput("--steps above 1e12 cannot be meant");
    return start + *o.steps;
  }
  if (o.time) return start + steps_of(*o.time, m.dt, "--time");
  uint64_t end = steps_of(m.end_time, m.dt, "end_time");
  if (start >= end)
    throw BadInput("the restart state is at step " + std::to_string(start) + ", the case ends at step " +
                   std::to_string(end) + " (end_time): give --steps or --time to run further");
  return end;
}

// The case hash recorded in DIR/summary.json, or "" when there is none.
std::string folder_case_hash(const std::string& dir) {
  std::ifstream in(dir + "/summary.json");
  if (!in) return "";
  try {
    auto j = nlohmann::json::parse(in);
    return j.at("provenance").at("case_hash").get<std::string>();
  } catch (const std::exception&) {
    return "";
  }
}

// Readies the claimed folder; true when a restart continues the run already in it.
bool open_folder(const OutputFolder& folder, const CaseRunOptions& o, const CaseSpec& spec) {
  if (!o.restart.empty() && folder.holds_files() && !o.overwrite) {
    std::string there = folder_case_hash(folder.dir());
    if (there != case_hash(spec))
      throw OutputError("--out " + folder.dir() + " holds " +
                        (there.empty() ? "other files" : "a run of another case (or other --set values)") +
                        ": continue a run in its own folder with the case and --set values it ran with, or choose another --out");
    folder.remove_leftovers({"frames"});  // a killed run's half-written temporaries
    return true;
  }
  folder.make_ready(o.overwrite, {spec.path, o.restart});
  return false;
}

struct Schedule {
  uint64_t frame_every = 0, checkpoint_every = 0, target = 0;
  uint32_t batch = 200;
  // The next step at which something is written (or the run ends).
  uint64_t next_stop(uint64_t step) const {
    uint64_t next = std::min<uint64_t>(target, step + batch);
    for (uint64_t every : {frame_every, checkpoint_every})
      if (every) next = std::min(next, (step / every + 1) * every);
    return next;
  }
};

Schedule make_schedule(const Model& m, uint64_t target) {
  Schedule s;
  s.target = target;
  if (m.output_interval > 0) s.frame_every = std::max<uint64_t>(1, steps_of(m.output_interval, m.dt, "[output] interval"));
  double every = m.checkpoint_interval;
  if (every > 0) s.checkpoint_every = std::max<uint64_t>(1, steps_of(every, m.dt, "[output] checkpoint_interval"));
  // Batches end exactly on frame steps.
  if (s.frame_every) {
    s.batch = uint32_t(std::min<uint64_t>(s.frame_every, 200));
    while (s.frame_every % s.batch) --s.batch;
  }
  return s;
}

void print_result(const Simulation& sim, const RunOutput& output, const RunInfo& info, const std::string& state_out) {
  const Model& m = sim.model();
  auto e = sim.kinetic_energy();
  double wall = info.wall_seconds;
  std::printf("%s: %llu steps, t = %.4g s, %u contacts, kinetic energy %.6g J, %.3g particle-steps/s (%s)\n",
              output.name().c_str(), (unsigned long long)sim.step(), sim.time(), sim.contacts(), e.total(),
              wall > 0 ? double(m.n_particles) * double(sim.step() - info.restart.step) / wall : 0.0,
              format_duration(wall).c_str());
  for (const auto& w : info.wall_forces)  // every wall, untouched ones too (0 N)
    std::printf("  force on %-10s (%.4g, %.4g, %.4g) N\n", w.name.c_str(), w.fx, w.fy, w.fz);
  std::printf("wrote %s/summary.json", output.dir().c_str());
  if (output.frames_written()) std::printf(", %u frames in %s/frames", output.frames_written(), output.dir().c_str());
  if (!state_out.empty()) std::printf(", state %s", state_out.c_str());
  std::printf("\n");
}

// The end of a run, finished or stopped by a signal: series, summary, checkpoint or final state.
int finish_run(const Simulation& sim, RunOutput& output, RunInfo& info, const CaseRunOptions& o, int signal) {
  info.frames = output.frames_written();
  if (signal) {
    output.checkpoint(sim);
    info.status = signal == SIGINT ? "interrupted by SIGINT" : "interrupted by SIGTERM";
    write_run_summary(output.dir() + "/summary.json", sim, info);
    std::fprintf(stderr, "%s at step %llu (t = %.6g s): wrote the summary and %s; continue with --restart %s\n",
                 info.status.c_str(), (unsigned long long)sim.step(), sim.time(), output.checkpoint_path().c_str(),
                 output.checkpoint_path().c_str());
    return 128 + signal;
  }
  if (sim.model().checkpoint_interval > 0) output.checkpoint(sim);
  output.write_series();
  info.status = "finished";
  write_run_summary(output.dir() + "/summary.json", sim, info);
  if (!o.state_out.empty()) write_state_file(o.state_out, sim.state(), sim.step(), sim.time(), output.case_hash());
  print_result(sim, output, info, o.state_out);
  return 0;
}

// Steps to the schedule's target, writing frames and checkpoints as they fall due; returns the
// signal that stopped it (0 when it got there).
int step_to_target(Simulation& sim, RunOutput& output, const Schedule& schedule, const CaseRunOptions& o,
                   const std::function<void()>& checkpointed) {
  const Model& m = sim.model();
  EscapeCheck escapes(m);
  bool escape_told = false;
  install_stop_handlers();
  Progress progress(output.name(), schedule.target, m.dt, !o.quiet, sim.step());
  int signal = 0;
  while (sim.step() < schedule.target && !(signal = stop_requested())) {
    sim.advance(schedule.next_stop(sim.step()) - sim.step(), [&](const Simulation& s) {
      progress.update(s.step(), std::to_string(s.contacts()) + " contacts");
    });
    // Checked on the positions alone, in the device's order (16 B per particle, not the whole
    // state: a batch nothing else reads is neither downloaded nor turned to global ids); an escape
    // found is then named by its global id. On the host, not in a kernel: the check stays one
    // double-precision function for both backends, with no twin to keep, and reads the very bytes
    // a full download would give.
    if (!escape_told && escapes.find(sim.rows_in_any_order(&HostState::pos), sim.time()))
      if (auto e = escapes.find(sim.state().pos, sim.time())) {
        escape_told = true;
        std::fprintf(stderr, "warning: at t = %.6g s particle %u is %s: it passed through (too fast for the time step, "
                             "or pushed through by a moving wall?); the run goes on\n", sim.time(), e->particle, e->where.c_str());
      }
    if (output.frame_due(sim.step())) output.frame(sim);
    if (schedule.checkpoint_every && sim.step() % schedule.checkpoint_every == 0) {
      output.checkpoint(sim);
      checkpointed();
    }
  }
  progress.finish();
  return signal ? signal : stop_requested();
}

RunInfo run_info(const CaseSpec& spec, const CaseRunOptions& o, const Backend& engine, const KernelVariant& variant) {
  RunInfo info;
  info.backend = engine.describe();
  info.variant = variant.name();
  Provenance prov = provenance_of(spec, o.overrides);
  prov.backend = o.backend;
  prov.device = info.backend;
  info.provenance = provenance_json(prov);
  return info;
}

}  // namespace

int run_case_to_folder(CaseSpec spec, const CaseRunOptions& o) {
  // Everything the user gave is checked before the folder is touched: the restart state (its
  // checksum, consistency and case), the step counts, the paths.
  Model model = build_model(spec);
  // Every variant gives the same bytes; the default is each backend's fastest (README, Speed).
  KernelVariant variant = o.variant.empty() ? KernelVariant::fastest_for(o.backend, model) : KernelVariant::parse(o.variant);
  const std::string hash = case_hash(spec);
  bool restarting = !o.restart.empty();
  RestartPoint start = restarting ? read_restart_state(o.restart, model, hash) : RestartPoint{};
  Schedule schedule = make_schedule(model, target_step(o, model, start.info.step));
  // The model holds the particles now: the case's own copies (~200 B each) are let go.
  std::vector<SphereSpec>().swap(spec.spheres);
  std::vector<BodySpec>().swap(spec.bodies);
  // The memory it needs fits (or the run is refused), before anything is written.
  uint32_t restart_capacity = restarting ? restored_capacity(model, start.state) : 0;
  MemoryNeed need = check_run_memory(model, variant, schedule.batch, o.backend, o.device,
                                     model.vtk && schedule.frame_every > 0, restart_capacity);
  if (!o.quiet) std::fprintf(stderr, "%s: memory: %s\n", spec.name.c_str(), describe_memory_need(need).c_str());
  std::string dir = o.out_dir.empty() ? "out/" + spec.name : o.out_dir;
  bool state_in_folder = !o.state_out.empty() && path_is_within(o.state_out, dir);
  if (!o.state_out.empty() && !state_in_folder) check_file_writable(o.state_out, "--state-out");
  OutputFolder folder(dir);  // ours alone until the run ends
  bool continuing = open_folder(folder, o, spec);
  if (state_in_folder) check_file_writable(o.state_out, "--state-out");

  auto engine = make_backend(o.backend, o.device, o.threads, variant.workgroup);
  RunInfo info = run_info(spec, o, *engine, variant);
  if (restarting) info.restart = {o.restart, start.info.step};
  Simulation sim(std::move(model), std::move(engine), variant, schedule.batch);
  if (restarting) sim.restore(start.state, start.info.step);
  if (o.wall_impulses) sim.sum_wall_forces();
  const Model& m = sim.model();
  RunOutput output(dir, spec.name, hash, m, schedule.frame_every, m.vtk, o.wall_impulses);
  auto summary = [&](const std::string& status) {
    info.status = status;
    info.frames = output.frames_written();
    write_run_summary(dir + "/summary.json", sim, info);
  };
  auto t0 = std::chrono::steady_clock::now();
  try {
    output.begin(sim.step(), continuing);
    summary("running");
    if (!o.quiet)
      std::fprintf(stderr, "%s: %u particles, %zu walls, dt %.3g s (%.2g%% of Rayleigh %.3g s), steps %llu to %llu on %s\n",
                   spec.name.c_str(), m.n_particles, m.wall_group_names().size(), m.dt, 100 * m.dt / m.rayleigh_time, m.rayleigh_time,
                   (unsigned long long)sim.step(), (unsigned long long)schedule.target, info.backend.c_str());
    if (!restarting && output.frame_due(0)) output.frame(sim);
    int signal = step_to_target(sim, output, schedule, o, [&] { summary("running"); });
    info.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    info.wall_forces = sim.wall_forces();
    return finish_run(sim, output, info, o, signal);
  } catch (const std::exception& e) {
    // The summary tells what stopped the run, with the system's reason for a failed write.
    info.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    try {
      summary(std::string("failed: ") + e.what());
    } catch (const std::exception& also) {
      std::fprintf(stderr, "repose run: the summary could not say so either: %s\n", also.what());
    }
    throw;
  }
}

}  // namespace repose
