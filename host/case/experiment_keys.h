// The [experiment] table of a case is read by the experiment its `type` names. Experiments live
// above the case layer (host/experiments: they run simulations), so the program hands the loader
// their readers once at start: install_experiments() (experiments/registry.h), called by main()
// and by the test runner. The loader itself knows no experiment by name.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "case/case_spec.h"
#include "case/toml_section.h"

namespace repose {

struct ExperimentKeyReader {
  std::string type;               // the [experiment] type
  std::vector<std::string> keys;  // its keys besides type and max_time
  std::function<void(const Section&, ExperimentSpec&)> read;
};

void set_experiment_key_readers(std::vector<ExperimentKeyReader> readers);
// Empty until the experiments are installed.
const std::vector<ExperimentKeyReader>& experiment_key_readers();

}  // namespace repose
