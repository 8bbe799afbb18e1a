// What a campaign sees of the experiment registry (experiments/registry.h): the experiment types
// by name, the responses each can report (for checking plans), and a run that returns them.
#pragma once
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "case/case_spec.h"
#include "engine/backend.h"

namespace repose::calibrate {

struct ExperimentOptions {
  std::string backend = kLibraryBackend;  // each simulation single-threaded on the cpu backend by default
  int device = -1;
  unsigned threads = 1;
  std::string picture_path;     // non-empty: save the experiment's picture there (a heap's PNG)
};

using Responses = std::map<std::string, double>;
using ExperimentFunction = std::function<Responses(const CaseSpec&, const ExperimentOptions&)>;

struct ExperimentType {
  std::string name;
  std::vector<std::string> responses;  // the names its function may return, for checking plans
  ExperimentFunction run;
};

// Every experiment type, by name.
const std::map<std::string, ExperimentType>& experiments();
// Throws std::runtime_error listing the registered names when `name` is not one of them.
const ExperimentType& find_experiment(const std::string& name);

}  // namespace repose::calibrate
