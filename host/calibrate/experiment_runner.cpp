#include "calibrate/experiment_runner.h"

#include <stdexcept>

#include "experiments/drop.h"

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

void register_experiment(std::map<std::string, ExperimentType>& table, ExperimentType type) {
  std::string name = type.name;
  table.emplace(std::move(name), std::move(type));
}

}  // namespace

const std::map<std::string, ExperimentType>& experiments() {
  static const std::map<std::string, ExperimentType> table = [] {
    std::map<std::string, ExperimentType> t;
    register_experiment(t, {"drop", {"restitution", "rebound_height", "rebound_height_exact", "contact_time", "impact_speed"}, drop_responses});
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
