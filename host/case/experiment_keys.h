// The [experiment] table of a case is read by the experiment its `type` names. Experiments live
// above the case layer (host/experiments: they run simulations), so the program hands the loader
// their readers once at start: install_experiments() (experiments/registry.h), called by main()
// and by the test runner. The loader knows no experiment, none of their keys and no wall one
// names: a reader lists its keys and those whose value names a [[wall]] (the loader checks that
// such a wall exists once every wall is read), and returns the experiment's settings.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "case/case_spec.h"
#include "case/toml_section.h"

namespace repose {

struct ExperimentKeyReader {
  std::string type;                    // the [experiment] type
  std::vector<std::string> keys;       // its keys besides type and max_time
  std::vector<std::string> wall_keys;  // those of them whose value is the name of a [[wall]]
  // ExperimentSpec::settings; errors name the key (CaseError).
  std::function<std::shared_ptr<const ExperimentSettings>(const Section&)> read;
};

void set_experiment_key_readers(std::vector<ExperimentKeyReader> readers);
// Empty until the experiments are installed.
const std::vector<ExperimentKeyReader>& experiment_key_readers();

}  // namespace repose
