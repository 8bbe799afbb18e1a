// A long experiment (a heap of a million grains takes hours on a CPU) that can stop and go on:
// - every `[output] checkpoint_interval` simulated seconds, and when SIGINT or SIGTERM asks it
//   to stop, it writes DIR/checkpoint.state (the simulation, io/state_file.h) and
//   DIR/checkpoint.json (what the experiment has gathered so far), each whole or not at all;
// - after a stop it throws ExperimentStopped (exit code 128 + the signal, no result written);
// - `repose experiment TYPE CASE --restart DIR/checkpoint.state` reads both back, checked against
//   the case, each other and the experiment, and the experiment goes on to the bytes of a run
//   that never stopped.
// An experiment takes part by saving and loading its own progress (Experiment::resumable()).
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

#include "experiments/experiment.h"

namespace repose {

class Simulation;
struct RunProfile;
struct WallForceSeries;

// A stop asked for by a signal, after the checkpoint was written.
struct ExperimentStopped : std::runtime_error {
  ExperimentStopped(const std::string& what, int signal) : std::runtime_error(what), signal(signal) {}
  int signal;
};

// The progress file beside a checkpoint's state file: DIR/checkpoint.state -> DIR/checkpoint.json.
std::string checkpoint_progress_path(const std::string& state_path);

// The checks restore() makes, before anything is run or written (`repose experiment --restart`).
// Throws InputError naming the file.
void check_experiment_restart(const CaseSpec& spec, const std::string& restart, const std::string& experiment_id);

class ExperimentCheckpoints {
 public:
  // `run.checkpoint_dir` empty: neither checkpoints nor stops (a calibration's or diagnosis's runs).
  ExperimentCheckpoints(const ExperimentRunOptions& run, const CaseSpec& spec, std::string experiment_id);
  // With run.restart: the state restored into sim and the experiment's progress returned; else
  // nullopt. Throws InputError (exit code 2) naming the file when either is not this
  // experiment's, this case's, or of the same step.
  std::optional<OrderedJson> restore(Simulation& sim) const;
  // After each sample: writes a checkpoint when one is due or a stop was asked for (`progress`
  // gives the experiment's JSON), then throws ExperimentStopped on a stop.
  void after_sample(const Simulation& sim, const std::function<OrderedJson()>& progress);
  // The checkpoints this object wrote and the wall time they took (the state read back from the
  // device, put in global order, hashed and written; the progress file).
  uint64_t written() const { return written_; }
  double write_seconds() const { return write_seconds_; }

 private:
  std::string dir_, restart_, id_, hash_, case_path_;
  uint64_t every_steps_ = 0, next_ = 0;
  uint64_t written_ = 0;
  double write_seconds_ = 0;
  void write(const Simulation& sim, const OrderedJson& progress);
};

// What experiments save in their progress: a kernel profile and a wall-force series, exactly
// (doubles as JSON numbers read back to the same bits).
OrderedJson profile_json(const RunProfile& p);
RunProfile profile_from_json(const OrderedJson& j);
OrderedJson wall_series_json(const WallForceSeries& s);
WallForceSeries wall_series_from_json(const OrderedJson& j);

}  // namespace repose
