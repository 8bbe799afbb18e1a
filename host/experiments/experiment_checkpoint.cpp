#include "experiments/experiment_checkpoint.h"

#include <csignal>
#include <cstdio>
#include <cmath>
#include <fstream>
#include <sstream>

#include "case/case_loader.h"
#include "engine/model.h"
#include "engine/run_profile.h"
#include "engine/simulation.h"
#include "experiments/wall_force_series.h"
#include "io/restart_state.h"
#include "io/state_file.h"
#include "util/atomic_file.h"
#include "util/input_error.h"
#include "util/stop_signal.h"

namespace repose {

std::string checkpoint_progress_path(const std::string& state_path) {
  std::string base = state_path;
  const std::string ext = ".state";
  if (base.size() > ext.size() && base.compare(base.size() - ext.size(), ext.size(), ext) == 0)
    base.resize(base.size() - ext.size());
  return base + ".json";
}

ExperimentCheckpoints::ExperimentCheckpoints(const ExperimentRunOptions& run, const CaseSpec& spec,
                                             std::string experiment_id)
    : dir_(run.checkpoint_dir), restart_(run.restart), id_(std::move(experiment_id)), hash_(case_hash(spec)),
      case_path_(spec.path) {
  if (!dir_.empty()) install_stop_handlers();
}

namespace {

struct Checkpoint {
  RestartPoint start;
  OrderedJson progress;
};

// The state file and the progress beside it, each checked against the case, the experiment and
// the other. Throws InputError naming the file.
Checkpoint read_checkpoint(const std::string& restart, const Model& model, const std::string& hash,
                           const std::string& id, const std::string& case_path) {
  Checkpoint c{read_restart_state(restart, model, hash), {}};
  const std::string path = checkpoint_progress_path(restart);
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(path, 0, 0,
                     "cannot read it: `repose experiment` keeps what it has gathered beside its checkpoint.state; "
                     "restart from the checkpoint in the experiment's own folder");
  std::stringstream text;
  text << in.rdbuf();
  OrderedJson j = OrderedJson::parse(text.str(), nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("progress") || !j.contains("step") ||
      !j["step"].is_number_unsigned())
    throw InputError(path, 0, 0, "not an experiment's checkpoint (damaged, or not written by repose experiment)");
  if (j.value("experiment", "") != id)
    throw InputError(path, 0, 0, "a checkpoint of the " + j.value("experiment", std::string("?")) +
                                     " experiment, not of " + id);
  if (j.value("case_hash", "") != hash)
    throw InputError(path, 0, 0, "a checkpoint of another case (or other --set values) than " + case_path);
  if (j["step"].get<uint64_t>() != c.start.info.step)
    throw InputError(path, 0, 0, "is at step " + std::to_string(j["step"].get<uint64_t>()) + ", " + restart +
                                     " at step " + std::to_string(c.start.info.step) +
                                     ": the two were not written together");
  c.progress = j["progress"];
  return c;
}

}  // namespace

void check_experiment_restart(const CaseSpec& spec, const std::string& restart, const std::string& experiment_id) {
  read_checkpoint(restart, build_model(spec), case_hash(spec), experiment_id, spec.path);
}

std::optional<OrderedJson> ExperimentCheckpoints::restore(Simulation& sim) const {
  if (restart_.empty()) return std::nullopt;
  Checkpoint c = read_checkpoint(restart_, sim.model(), hash_, id_, case_path_);
  sim.restore(c.start.state, c.start.info.step);
  return c.progress;
}

void ExperimentCheckpoints::after_sample(const Simulation& sim, const std::function<OrderedJson()>& progress) {
  if (dir_.empty()) return;
  const Model& m = sim.model();
  if (every_steps_ == 0 && m.checkpoint_interval > 0) {
    every_steps_ = std::max<uint64_t>(1, uint64_t(std::llround(m.checkpoint_interval / m.dt)));
    next_ = (sim.step() / every_steps_ + 1) * every_steps_;
  }
  int signal = stop_requested();
  bool due = every_steps_ > 0 && sim.step() >= next_;
  if (!due && signal == 0) return;
  write(sim, progress());
  if (due) next_ = (sim.step() / every_steps_ + 1) * every_steps_;
  if (signal != 0) {
    std::string state = dir_ + "/checkpoint.state";
    char where[96];
    std::snprintf(where, sizeof where, " at step %llu (t = %.6g s)", (unsigned long long)sim.step(), sim.time());
    throw ExperimentStopped(std::string(signal == SIGINT ? "interrupted by SIGINT" : "interrupted by SIGTERM") + where +
                                ": wrote " + state + " and " + checkpoint_progress_path(state) +
                                "; continue with --restart " + state + " --out " + dir_,
                            signal);
  }
}

void ExperimentCheckpoints::write(const Simulation& sim, const OrderedJson& progress) {
  ProfileClock clock(&write_seconds_);
  ++written_;
  const std::string state = dir_ + "/checkpoint.state";
  OrderedJson j;
  j["experiment"] = id_;
  j["case"] = case_path_;
  j["case_hash"] = hash_;
  j["step"] = sim.step();
  j["time_s"] = sim.time();
  j["progress"] = progress;
  // The state first: a stop between the two leaves files of different steps, which a restart refuses.
  write_state_file(state, sim.state(), sim.step(), sim.time(), hash_);
  write_file_atomically(checkpoint_progress_path(state), j.dump(1) + "\n");
}

OrderedJson profile_json(const RunProfile& p) {
  OrderedJson kernels = OrderedJson::object();
  for (const auto& [name, seconds] : p.kernels) kernels[name] = seconds;
  return {{"wall_seconds", p.wall_seconds},
          {"steps", p.steps},
          {"rebuilds", p.rebuilds},
          {"contact_steps", p.contact_steps},
          {"reorders", p.reorders},
          {"reorder_seconds", p.reorder_seconds},
          {"reorder_download_seconds", p.reorder_parts.download},
          {"reorder_order_seconds", p.reorder_parts.order},
          {"reorder_upload_seconds", p.reorder_parts.upload},
          {"batch_seconds", p.batch_seconds},
          {"pipeline_seconds", p.device.pipelines},
          {"recording_seconds", p.device.recording},
          {"between_kernels_seconds", p.device.between_kernels},
          {"transfer_seconds", p.transfer_seconds},
          {"kernels", kernels}};
}

RunProfile profile_from_json(const OrderedJson& j) {
  RunProfile p;
  p.wall_seconds = j.at("wall_seconds").get<double>();
  p.steps = j.at("steps").get<uint64_t>();
  p.rebuilds = j.at("rebuilds").get<uint64_t>();
  p.contact_steps = j.at("contact_steps").get<double>();
  p.reorders = j.value("reorders", uint64_t(0));  // absent before they were timed
  p.reorder_seconds = j.value("reorder_seconds", 0.0);
  p.reorder_parts.download = j.value("reorder_download_seconds", 0.0);  // these three absent before 2026-11-28
  p.reorder_parts.order = j.value("reorder_order_seconds", 0.0);
  p.reorder_parts.upload = j.value("reorder_upload_seconds", 0.0);
  p.batch_seconds = j.value("batch_seconds", 0.0);  // these five absent before they were timed
  p.device.pipelines = j.value("pipeline_seconds", 0.0);
  p.device.recording = j.value("recording_seconds", 0.0);
  p.device.between_kernels = j.value("between_kernels_seconds", 0.0);
  p.transfer_seconds = j.value("transfer_seconds", 0.0);
  for (const auto& [name, seconds] : j.at("kernels").items()) p.kernels[name] = seconds.get<double>();
  return p;
}

OrderedJson wall_series_json(const WallForceSeries& s) {
  OrderedJson rows = OrderedJson::array(), impulses = OrderedJson::array();
  for (const auto& row : s.rows) {
    OrderedJson r = OrderedJson::array();
    for (const WallForce& f : row) r.push_back({f.name, f.fx, f.fy, f.fz});
    rows.push_back(r);
  }
  for (const auto& row : s.impulses) {
    OrderedJson r = OrderedJson::array();
    for (const WallImpulse& w : row) r.push_back({w.name, w.jx, w.jy, w.jz, w.peak});
    impulses.push_back(r);
  }
  return {{"names", s.names}, {"times", s.times}, {"rows", rows}, {"impulses", impulses}};
}

WallForceSeries wall_series_from_json(const OrderedJson& j) {
  WallForceSeries s;
  s.names = j.at("names").get<std::vector<std::string>>();
  s.times = j.at("times").get<std::vector<double>>();
  for (const auto& r : j.at("rows")) {
    std::vector<WallForce> row;
    for (const auto& f : r) row.push_back({f.at(0).get<std::string>(), f.at(1).get<double>(), f.at(2).get<double>(), f.at(3).get<double>()});
    s.rows.push_back(row);
  }
  for (const auto& r : j.at("impulses")) {
    std::vector<WallImpulse> row;
    for (const auto& w : r)
      row.push_back({w.at(0).get<std::string>(), w.at(1).get<double>(), w.at(2).get<double>(), w.at(3).get<double>(),
                     w.at(4).get<double>()});
    s.impulses.push_back(row);
  }
  return s;
}

}  // namespace repose
