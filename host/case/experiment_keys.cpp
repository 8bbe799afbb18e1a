#include "case/experiment_keys.h"

namespace repose {

namespace {
std::vector<ExperimentKeyReader>& readers() {
  static std::vector<ExperimentKeyReader> table;
  return table;
}
}  // namespace

void set_experiment_key_readers(std::vector<ExperimentKeyReader> r) { readers() = std::move(r); }

const std::vector<ExperimentKeyReader>& experiment_key_readers() { return readers(); }

}  // namespace repose
