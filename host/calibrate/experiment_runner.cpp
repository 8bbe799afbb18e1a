#include "calibrate/experiment_runner.h"

#include <stdexcept>

#include "experiments/drop.h"
#include "experiments/repose.h"
#include "experiments/roll.h"
#include "experiments/tilt.h"
#include "measure/heap_png.h"

namespace repose::calibrate {

namespace {

Responses drop_responses(const CaseSpec& spec, const ExperimentOptions& o) {
  DropResult r = run_drop(spec, {o.backend, o.device, o.threads});
  return {{"restitution", r.restitution},
          {"rebound_height", r.rebound_height},
          {"rebound_height_exact", r.rebound_height_exact},
          {"contact_time", r.contact_time},
          {"impact_speed", r.impact_speed}};
}

ExperimentRunOptions run_options(const ExperimentOptions& o) { return {o.backend, o.device, o.threads, false}; }

// slide, and roll with method "tilt": the plate tilts until the body moves.
Responses tilt_responses(const CaseSpec& spec, const ExperimentOptions& o) {
  TiltResult r = run_tilt(spec, run_options(o));
  return {{"onset_angle_deg", r.onset_angle_deg}, {"tan_alpha", r.tan_alpha}, {"onset_time", r.onset_time},
          {"rolled_fraction", r.rolled_fraction}};
}

Responses roll_responses(const CaseSpec& spec, const ExperimentOptions& o) {
  if (spec.experiment.method == "tilt") return tilt_responses(spec, o);
  RollResult r = run_roll(spec, run_options(o));
  return {{"rolling_distance", r.rolling_distance}, {"mu_r", r.mu_r}, {"stop_time", r.stop_time},
          {"speed_at_foot", r.speed_at_foot}};
}

Responses repose_responses(const CaseSpec& spec, const ExperimentOptions& o) {
  ReposeResult r = run_repose(spec, run_options(o));
  if (!o.picture_path.empty()) write_heap_angle_png(o.picture_path, r.heap);
  Responses out = {{"angle", r.angle_deg}, {"heap_height", r.heap.heap_height}, {"settle_time", r.settle_time},
                   {"particles_measured", double(r.particles_measured)}};
  if (r.heap_3d && r.heap_3d->valid_sectors > 0) out["angle_3d"] = r.heap_3d->mean_deg;
  out["angle_front"] = r.heap.mean_deg;  // the single front view, also when the angle is several views' mean
  if (r.views) out["angle_views_sd"] = r.views->sd_deg;
  return out;
}

void register_experiment(std::map<std::string, ExperimentType>& table, ExperimentType type) {
  std::string name = type.name;
  table.emplace(std::move(name), std::move(type));
}

}  // namespace

const std::map<std::string, ExperimentType>& experiments() {
  static const std::map<std::string, ExperimentType> table = [] {
    std::map<std::string, ExperimentType> t;
    register_experiment(t, {"drop", {"restitution", "rebound_height", "rebound_height_exact", "contact_time", "impact_speed"}, drop_responses});
    register_experiment(t, {"slide", {"onset_angle_deg", "tan_alpha", "onset_time", "rolled_fraction"}, tilt_responses});
    register_experiment(t, {"roll", {"rolling_distance", "mu_r", "stop_time", "speed_at_foot", "onset_angle_deg", "tan_alpha",
                                     "onset_time", "rolled_fraction"}, roll_responses});
    register_experiment(t, {"repose", {"angle", "angle_3d", "angle_front", "angle_views_sd", "heap_height", "settle_time", "particles_measured"}, repose_responses});
    return t;
  }();
  return table;
}

const ExperimentType& find_experiment(const std::string& name) {
  auto it = experiments().find(name);
  if (it != experiments().end()) return it->second;
  std::string known;
  for (const auto& [n, t] : experiments()) known += (known.empty() ? "" : ", ") + n;
  throw std::runtime_error("unknown experiment '" + name + "' (registered: " + known + ")");
}

}  // namespace repose::calibrate
