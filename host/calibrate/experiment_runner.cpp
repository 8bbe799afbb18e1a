#include "calibrate/experiment_runner.h"

#include <stdexcept>

#include "experiments/registry.h"

namespace repose::calibrate {

namespace {

// The registry's experiment of this type for the case (roll: by its method), run strictly: a
// reading the rig cannot take fails the run.
Responses run_type(const std::string& type, const CaseSpec& spec, const ExperimentOptions& o) {
  ExperimentRun run;
  run.backend = o.backend;
  run.device = o.device;
  run.threads = o.threads;
  run.picture_path = o.picture_path;
  ExperimentOutcome outcome = experiment_of_type(type, spec).run(spec, run);
  return measured_or_throw(outcome).values;
}

}  // namespace

const std::map<std::string, ExperimentType>& experiments() {
  static const std::map<std::string, ExperimentType> table = [] {
    std::map<std::string, ExperimentType> t;
    for (const std::string& type : experiment_types())
      t[type] = {type, responses_of_type(type),
                 [type](const CaseSpec& spec, const ExperimentOptions& o) { return run_type(type, spec, o); }};
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
