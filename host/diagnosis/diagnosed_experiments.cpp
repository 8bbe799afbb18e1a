#include "diagnosis/diagnosed_experiments.h"

namespace repose {

const std::vector<DiagnosedExperiment>& diagnosed_experiments() {
  static const std::vector<DiagnosedExperiment> table = {
      {"drop",
       {"rebound_height", "restitution", "height"},
       {"restitution", "1", 0.05, 0.95, false},
       [](CaseSpec& s) -> double& { return body_plate_interaction(s).restitution; },
       "Hertz-Mindlin, constant restitution",
       "experiment.drop_height"},
      {"repose",
       {"repose_angle", "bed_height", "heap_height", "runout", "profile_convexity"},
       {"static_friction", "1", 0.05, 1.2, false},
       [](CaseSpec& s) -> double& { return heap_interaction(s).static_friction; },
       "Hertz-Mindlin, one grain size, constant rolling torque",
       "fill.0.count"},
      {"slide",
       {"slide_angle"},
       {"static_friction", "1", 0.05, 1.2, false},
       [](CaseSpec& s) -> double& { return body_plate_interaction(s).static_friction; },
       "Hertz-Mindlin, Coulomb friction, no cohesion",
       "material.0.density"},
      // Rolling friction spans decades between a ball bearing and a cabbage: searched in log.
      {"roll",
       {"roll_distance"},
       {"rolling_friction", "1", kSmallestRollingFriction, 0.3, true},
       [](CaseSpec& s) -> double& { return body_plate_interaction(s).rolling_friction; },
       "Hertz-Mindlin, constant rolling torque, no air",
       "experiment.slope_distance"},
      {"roll_tilt",
       {"roll_angle"},
       {"rolling_friction", "1", kSmallestRollingFriction, 0.3, true},
       [](CaseSpec& s) -> double& { return body_plate_interaction(s).rolling_friction; },
       "Hertz-Mindlin, constant rolling torque, no cohesion",
       "material.0.density"},
  };
  return table;
}

const DiagnosedExperiment* diagnosed_experiment(const CaseSpec& spec) {
  std::string id = spec.experiment.type;
  if (id == "roll" && spec.experiment.method == "tilt") id = "roll_tilt";
  for (const auto& e : diagnosed_experiments())
    if (e.id == id) return &e;
  return nullptr;
}

}  // namespace repose
