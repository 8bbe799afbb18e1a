// The one registry through which a campaign reaches the virtual experiments: an experiment
// type ("drop", ...) maps to a function that runs a loaded case and returns named responses.
// Adding an experiment is one `register_experiment` line in experiment_runner.cpp.
#pragma once
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "case/case_spec.h"

namespace repose::calibrate {

struct ExperimentOptions {
  std::string backend = "cpu";  // each simulation single-threaded on the cpu backend by default
  int device = -1;
  unsigned threads = 1;
};

using Responses = std::map<std::string, double>;
using ExperimentFunction = std::function<Responses(const CaseSpec&, const ExperimentOptions&)>;

struct ExperimentType {
  std::string name;
  std::vector<std::string> responses;  // the names its function returns, for checking plans
  ExperimentFunction run;
};

// Every registered experiment, by name.
const std::map<std::string, ExperimentType>& experiments();
// Throws std::runtime_error listing the registered names when `name` is not one of them.
const ExperimentType& find_experiment(const std::string& name);

}  // namespace repose::calibrate
