#include "experiments/registry.h"

#include <algorithm>
#include <stdexcept>

#include "case/experiment_keys.h"

namespace repose {

// Every experiment, in order: the first of a type that handles a case runs it. A row NAME is the
// experiment's `const Experiment& NAME_experiment()`, defined in its own file. Adding an
// experiment: its own files in host/experiments, and one row here.
#define REPOSE_EXPERIMENT_LIST(X) \
  X(drop_on_bed) /* before drop: it takes the drop cases that hold a fixed bed */ \
  X(drop)                                                                        \
  X(slide)                                                                       \
  X(roll)                                                                        \
  X(roll_tilt)                                                                   \
  X(repose)                                                                      \
  X(drain)

#define REPOSE_DECLARE_EXPERIMENT(name) const Experiment& name##_experiment();
REPOSE_EXPERIMENT_LIST(REPOSE_DECLARE_EXPERIMENT)
#undef REPOSE_DECLARE_EXPERIMENT

const std::vector<const Experiment*>& experiments() {
  static const std::vector<const Experiment*> list = {
#define REPOSE_LIST_EXPERIMENT(name) &name##_experiment(),
      REPOSE_EXPERIMENT_LIST(REPOSE_LIST_EXPERIMENT)
#undef REPOSE_LIST_EXPERIMENT
  };
  return list;
}

const Experiment* experiment_for(const CaseSpec& spec) {
  for (const Experiment* e : experiments())
    if (e->type() == spec.experiment.type && e->handles(spec)) return e;
  return nullptr;
}

const Experiment& experiment_of_type(const std::string& type, const CaseSpec& spec) {
  for (const Experiment* e : experiments())
    if (e->type() == type && e->handles(spec)) return *e;
  std::string known;
  for (const auto& t : experiment_types()) known += (known.empty() ? "" : ", ") + t;
  throw std::runtime_error("unknown experiment '" + type + "' (" + known + ")");
}

std::vector<std::string> experiment_types() {
  std::vector<std::string> types;
  for (const Experiment* e : experiments())
    if (std::find(types.begin(), types.end(), e->type()) == types.end()) types.push_back(e->type());
  return types;
}

std::vector<std::string> responses_of_type(const std::string& type) {
  std::vector<std::string> names;
  for (const Experiment* e : experiments())
    if (e->type() == type)
      for (const auto& r : e->responses())
        if (std::find(names.begin(), names.end(), r) == names.end()) names.push_back(r);
  return names;
}

std::vector<MeasureInfo> diagnosed_measures() {
  std::vector<MeasureInfo> measures;
  for (const Experiment* e : experiments())
    if (const DiagnosisRole* role = e->diagnosis())
      for (const MeasureInfo& m : role->measures)
        if (std::none_of(measures.begin(), measures.end(), [&](const MeasureInfo& k) { return k.name == m.name; }))
          measures.push_back(m);
  return measures;
}

void install_experiments() {
  std::vector<ExperimentKeyReader> readers;
  for (const Experiment* e : experiments()) {
    bool known = std::any_of(readers.begin(), readers.end(), [&](const auto& r) { return r.type == e->type(); });
    if (!known)
      readers.push_back({e->type(), e->keys(), e->wall_keys(), [e](const Section& s) { return e->read_keys(s); }});
  }
  set_experiment_key_readers(std::move(readers));
}

}  // namespace repose
