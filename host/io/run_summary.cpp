#include "io/run_summary.h"

#include <nlohmann/json.hpp>

#include "util/atomic_file.h"

namespace repose {

void write_run_summary(const std::string& path, const Simulation& sim, const RunInfo& info) {
  const Model& m = sim.model();
  auto energy = sim.kinetic_energy();
  nlohmann::ordered_json j;
  j["status"] = info.status;
  j["case"] = m.case_path;
  j["backend"] = info.backend;
  j["variant"] = info.variant;
  j["particles"] = m.n_particles;
  j["steps"] = sim.step();
  j["time"] = sim.time();
  j["dt"] = m.dt;
  j["rayleigh_time"] = m.rayleigh_time;
  j["dt_fraction_of_rayleigh"] = m.dt / m.rayleigh_time;
  j["contacts"] = sim.contacts();
  j["list_rebuilds"] = sim.rebuilds();
  j["kinetic_energy"] = {{"translational", energy.translational},
                         {"rotational", energy.rotational},
                         {"total", energy.total()}};
  j["total_mass"] = m.total_mass;
  auto walls = nlohmann::ordered_json::array();
  for (const auto& w : info.wall_forces)
    walls.push_back({{"name", w.name}, {"force", {w.fx, w.fy, w.fz}}});
  j["wall_forces"] = walls;
  j["frames"] = info.frames;
  j["wall_seconds"] = info.wall_seconds;
  // Of this invocation: a restarted run counts the steps since its restart.
  j["particle_steps_per_second"] =
      info.wall_seconds > 0 ? double(m.n_particles) * double(sim.step() - info.restart.step) / info.wall_seconds : 0.0;
  if (!info.restart.file.empty()) j["restarted_from"] = {{"file", info.restart.file}, {"step", info.restart.step}};
  j["provenance"] = info.provenance;
  // A failed run says so even on a full disk (over the old summary's bytes if need be).
  if (info.status.rfind("failed: ", 0) == 0)
    write_status_file(path, j.dump(2) + "\n");
  else
    write_file_atomically(path, j.dump(2) + "\n");
}

}  // namespace repose
