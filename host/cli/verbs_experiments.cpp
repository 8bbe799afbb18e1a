// `repose experiment TYPE CASE.toml`: the studies' lab tests as simulations, measured like the lab.
// The experiment the case names (experiments/registry.h) runs it, prints what it measured and
// writes TYPE.json with the files it declares (time series as CSV, wall forces, a heap's picture).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>

#include "cli/cli_case.h"
#include "cli/cli_checks.h"
#include "cli/verbs.h"
#include "util/number_text.h"
#include "engine/backend_factory.h"
#include "engine/model.h"
#include "experiments/experiment_checkpoint.h"
#include "experiments/registry.h"
#include "io/output_dir.h"
#include "io/provenance.h"

namespace repose::cli {

namespace {

std::string listed(const std::vector<std::string>& words) {
  std::string text;
  for (const auto& w : words) text += (text.empty() ? "" : ", ") + w;
  return text;
}

// The experiment types (each once) of the experiments for which `has` holds.
template <class Predicate>
std::vector<std::string> types_where(Predicate has) {
  std::vector<std::string> types;
  for (const Experiment* e : experiments())
    if (has(*e) && std::find(types.begin(), types.end(), e->type()) == types.end()) types.push_back(e->type());
  return types;
}

// The experiment types whose cases take `key` in their [experiment] table.
std::vector<std::string> types_with_key(const std::string& key) {
  return types_where([&](const Experiment& e) {
    const std::vector<std::string> keys = e.keys();
    return std::find(keys.begin(), keys.end(), key) != keys.end();
  });
}

// What produced an experiment's result (io/provenance.h); creating the backend names its device.
nlohmann::ordered_json experiment_provenance(const CaseSpec& spec, const std::vector<std::string>& sets,
                                             const ExperimentRun& run) {
  Provenance p = provenance_of(spec, sets);
  p.backend = run.backend;
  p.device = make_backend(run.backend, run.device, run.threads, gpu::kDefaultWorkgroup)->describe();
  nlohmann::ordered_json j = provenance_json(p);
  j["max_time"] = spec.experiment.max_time;  // the case's, or --max-time's
  return j;
}

// The verb's command line as parsed; the two options whose presence matters are kept to ask.
struct ExperimentArgs {
  std::string type, case_path, backend = kUserBackend, out_dir, restart;
  unsigned threads = 0;
  int device = -1;
  std::vector<std::string> sets;
  double height = 0, frames = 0, max_time = 0;
  bool quiet = false, overwrite = false, profile = false, wall_impulses = false;
  int replicates = 1;
  CLI::Option* height_option = nullptr;
  CLI::Option* frames_option = nullptr;
  CLI::Option* max_time_option = nullptr;
};

void add_experiment_options(CLI::App& app, ExperimentArgs& a) {
  app.add_option("type", a.type, "experiment: " + listed(experiment_types()))
      ->required()
      ->check(CLI::IsMember(experiment_types()));
  app.add_option("case", a.case_path, "case file (TOML) with an [experiment] table")->required();
  a.height_option = app.add_option("--height", a.height, "drop: height H of the lowest point (m); default from the case")
                        ->check(finite_positive());
  app.add_option("--backend", a.backend, "auto (default: a hardware GPU, else cpu; see `repose devices`), cpu or vulkan")
      ->check(CLI::IsMember({"auto", "vulkan", "cpu"}));
  app.add_option("--threads", a.threads, "cpu backend threads (default all cores)")->check(thread_count());
  app.add_option("--device", a.device, "Vulkan device index")->check(whole_number(0, 63));
  app.add_option("--set", a.sets, "override a case key: KEY=VALUE (repeatable)");
  app.add_option("--out", a.out_dir, "output folder, new or empty (default out/experiment/CASE_NAME)")
      ->check(non_empty_path());
  app.add_flag("--overwrite", a.overwrite, "delete what --out holds before the experiment");
  app.add_option("--restart", a.restart,
                 "repose: continue from DIR/checkpoint.state, which a stopped experiment (Ctrl-C, SIGTERM) or "
                 "[output] checkpoint_interval wrote, in its folder DIR: the result of a run that never stopped")
      ->check(CLI::ExistingFile);
  a.max_time_option =
      app.add_option("--max-time", a.max_time,
                     "give up by this simulated time (s) instead of the case's [experiment] max_time; not part of "
                     "the case's identity, so a --restart can go on past the time a heap had not settled by")
          ->check(finite_positive());
  app.add_flag("--quiet", a.quiet, "no progress output");
  app.add_flag("--profile", a.profile, "repose: time every kernel and print where each phase's time went");
  app.add_flag("--wall-impulses", a.wall_impulses,
               "wall_forces.csv also gives each wall's largest force and its impulse between samples (the walls' "
               "forces summed every step: one more kernel per step)");
  a.frames_option = app.add_option("--frames", a.frames,
                                   "write VTK frames (as `repose run`) every so many simulated seconds; alone: the "
                                   "case's [output] interval, else 0.01 s (less often for large cases)")
                        ->expected(0, 1)
                        ->check(finite_positive());
  app.add_option("--replicates", a.replicates,
                 "drop, roll (incline): N runs with seeds seed, seed+1, ... (a clump at a random orientation each)")
      ->check(whole_number(1, 1000));
}

// The case's [experiment] type must be the verb's, and --replicates must suit the experiment:
// 0 when both hold, else the exit code after the message.
int check_experiment_fits(const ExperimentArgs& a, const CaseSpec& spec, const Experiment* experiment) {
  if (spec.experiment.type != a.type || !experiment) {
    std::fprintf(stderr, "%s: [experiment] type is '%s', not '%s'\n", a.case_path.c_str(),
                 spec.experiment.type.c_str(), a.type.c_str());
    return 2;
  }
  if (!a.restart.empty() && !experiment->resumable()) {
    std::vector<std::string> with;
    for (const Experiment* e : experiments())
      if (e->resumable()) with.push_back(e->description());
    return usage_error("--restart applies to " + listed(with) + ", not to " + experiment->description());
  }
  if (a.replicates > 1 && !experiment->takes_replicates()) {
    std::vector<std::string> with;
    for (const Experiment* e : experiments())
      if (e->takes_replicates()) with.push_back(e->description());
    return usage_error("--replicates applies to " + listed(with) + ", not to " + experiment->description());
  }
  return 0;
}

// How the experiment runs: the chosen backend, the user's switches, and VTK frames when asked for
// or when the case's [output] writes them.
ExperimentRun experiment_run_for(const ExperimentArgs& a, const CaseSpec& spec, const BackendChoice& chosen) {
  ExperimentRun run;
  run.backend = chosen.backend;
  run.device = chosen.device;
  run.profile = a.profile;
  run.threads = a.threads;
  run.progress = !a.quiet;
  run.replicates = a.replicates;
  run.wall_impulses = a.wall_impulses;
  run.checkpoint_dir = a.out_dir;
  run.restart = a.restart;
  if (a.frames_option->count() || (spec.output.interval > 0 && spec.output.vtk)) {
    run.frames.dir = a.out_dir;
    run.frames.name = spec.name;
    run.frames.interval = a.frames > 0               ? a.frames
                          : spec.output.interval > 0 ? spec.output.interval
                                                     : default_frame_interval(build_model(spec), spec.experiment.max_time);
  }
  // Not strict: a reading the rig could not take comes back as a status with what was measured
  // so far, which is written (TYPE.json with status "failed" and the reason) before exit 1.
  run.strict = false;
  return run;
}

// Runs the experiment and writes TYPE.json whatever happens: its measurement, the reading it could
// not take (exit 1), or the error that stopped it.
int run_and_write_outcome(const Experiment& experiment, const CaseSpec& spec, const ExperimentRun& run,
                          const ExperimentArgs& a) {
  const std::string& out_dir = a.out_dir;
  try {
    ExperimentOutcome outcome = experiment.run(spec, run);
    outcome.json = with_status(outcome);
    outcome.json["provenance"] = experiment_provenance(spec, a.sets, run);
    if (!a.restart.empty()) outcome.json["provenance"]["restarted_from"] = a.restart;
    for (const std::string& line : write_outcome(outcome, a.type + ".json", out_dir))
      std::printf("%s\n", line.c_str());
    if (run.frames.wanted())
      std::printf("VTK frames every %g s in %s/frames, series %s/%s*.pvd for ParaView (*_contacts.pvd: the force "
                  "network, *_walls.pvd: the walls)\n",
                  run.frames.interval, out_dir.c_str(), out_dir.c_str(), spec.name.c_str());
    if (outcome.status != OutcomeStatus::Measured) {
      std::fprintf(stderr, "%s\n", outcome.problem.c_str());
      return 1;
    }
  } catch (const ExperimentStopped& e) {  // the checkpoint is written; no result yet
    std::fprintf(stderr, "%s\n", e.what());
    return 128 + e.signal;
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    ExperimentOutcome failed;
    failed.status = OutcomeStatus::Failed;
    failed.problem = e.what();
    failed.json["experiment"] = a.type;
    failed.json["case"] = spec.path;
    failed.json = with_status(failed);
    failed.json["provenance"] = experiment_provenance(spec, a.sets, run);
    write_outcome(failed, a.type + ".json", out_dir);
    return failure_exit_code(e);
  }
  return 0;
}

// The output folder, claimed and readied: emptied for a new experiment (with --overwrite), kept
// as it is for a restart, which must continue in its checkpoint's folder. False after the
// message when it cannot be used.
bool claim_output_folder(std::optional<OutputFolder>& folder, const ExperimentArgs& a,
                         const std::filesystem::path& checkpoint_home) {
  try {
    folder.emplace(a.out_dir);
    if (a.restart.empty()) {
      folder->make_ready(a.overwrite, {a.case_path});
    } else if (a.overwrite || !std::filesystem::equivalent(checkpoint_home, a.out_dir)) {
      throw OutputError("--restart continues in the folder of its checkpoint (" + a.restart +
                        "), kept as it is: --out that folder (or leave --out out), without --overwrite");
    } else {
      folder->remove_leftovers();  // a killed experiment's half-written temporaries
    }
  } catch (const OutputError& e) {
    std::fprintf(stderr, "repose experiment: %s\n", e.what());
    return false;
  }
  return true;
}

int run_experiment(int argc, char** argv) {
  std::string descriptions;
  for (const Experiment* e : experiments()) descriptions += (descriptions.empty() ? "" : ", ") + e->description();
  CLI::App app{"Run a virtual experiment: " + descriptions + "."};
  ExperimentArgs a;
  add_experiment_options(app, a);
  REPOSE_PARSE(app, argc, argv);
  const std::vector<std::string> with_height = types_with_key("drop_height");
  if (a.height_option->count() && std::find(with_height.begin(), with_height.end(), a.type) == with_height.end())
    return usage_error("--height applies to the " + listed(with_height) + " experiment");

  std::vector<CaseOverride> extra;
  if (a.height_option->count()) {
    extra.push_back({"experiment.drop_height", exact_number(a.height)});
    a.sets.push_back("experiment.drop_height=" + extra.back().value);  // recorded with the user's --set
  }
  auto loaded = load_case_or_report(a.case_path, a.sets, extra);
  if (!loaded) return 2;
  CaseSpec& spec = *loaded;
  // When to give up says nothing of the physics: set after loading, outside the case's identity
  // (as `repose run --time`), so a checkpoint of the same case continues under it.
  if (a.max_time_option->count()) {
    spec.experiment.max_time = a.max_time;
    spec.experiment.max_time_where = {spec.path, "--max-time", 0};
  }
  const Experiment* experiment = experiment_for(spec);
  if (int code = check_experiment_fits(a, spec, experiment)) return code;
  try {
    experiment->check_case(spec);
    if (!a.restart.empty()) check_experiment_restart(spec, a.restart, experiment->id());
  } catch (const BadInput& e) {
    std::fprintf(stderr, "repose experiment: %s\n", e.what());
    return 2;
  }
  // Its own default folder: `repose run` of the same case writes out/CASE_NAME; a restart
  // continues in the folder of its checkpoint.
  namespace fs = std::filesystem;
  const fs::path checkpoint_home = fs::path(a.restart).parent_path().empty() ? fs::path(".") : fs::path(a.restart).parent_path();
  if (a.out_dir.empty()) a.out_dir = a.restart.empty() ? "out/experiment/" + spec.name : checkpoint_home.string();
  const ExperimentRun run = experiment_run_for(a, spec, resolve_backend(a.backend, a.device));
  if (!a.restart.empty() && run.frames.wanted())
    return usage_error("--restart continues an experiment without VTK frames, and this one writes them (--frames or "
                       "the case's [output] interval)");
  std::optional<OutputFolder> folder;  // ours alone until the experiment ends
  if (!claim_output_folder(folder, a, checkpoint_home)) return 2;
  return run_and_write_outcome(*experiment, spec, run, a);
}

}  // namespace

std::vector<Verb> experiment_verbs() {
  return {{"experiment", "virtual lab test: " + listed(experiment_types()) + " (prints the result, writes JSON + CSV)",
           run_experiment}};
}

}  // namespace repose::cli
