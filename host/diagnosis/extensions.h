// The candidate model extensions of `repose diagnose` (docs/diagnosis.md). Each is one row of
// model_extensions() (extensions.cpp) that says everything about it except its kernel code: what
// it adds to the baseline Hertz-Mindlin model, where that physics lives, its parameters with their
// search ranges, the measures that reveal it, the case keys it sets and the `apply` that sets them.
// Diagnose, synth-data and `repose diagnose --extensions` read only this table.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "case/case_spec.h"
#include "stats/free_parameter.h"

namespace repose {

struct ModelExtension {
  std::string id;           // "air_drag"
  std::string description;  // one line for reports
  std::string physics;      // where its physics lives: "air_drag_acceleration() in shaders/kernels/kick.h"
  std::string case_keys;    // the case keys `apply` sets: "[air_drag] drag_coefficient, air_density"
  std::vector<FreeParameter> parameters;
  // Which measures can reveal it (names of experiments' MeasureInfo); empty: none of the
  // experiments diagnose runs yet (pending).
  std::vector<std::string> revealed_by;
  std::string pending_reason = "";  // why it cannot be tested yet, when revealed_by is empty
  // Writes the parameters (in `parameters` order) into a case.
  std::function<void(CaseSpec&, const std::vector<double>&)> apply;
  // Its signature is the replicate scatter (a stochastic model): tested only when the data give
  // sigma, since otherwise the scatter is taken as the measurement noise.
  bool needs_sigma = false;
  // Optional: the parameters with ranges that suit a given case (e.g. a heap's cohesion over the
  // Bond numbers of its grains); empty: `parameters` as listed, whatever the case.
  std::function<std::vector<FreeParameter>(const CaseSpec&)> parameters_for;
};

const std::vector<ModelExtension>& model_extensions();
const ModelExtension* find_extension(const std::string& id);

// The contact the case's experiment calibrates (Experiment::tested_contact: a drop's body and
// plate, a heap's grains with each other, ...), which contact-model extensions act on. Throws
// naming the case when it has none.
Interaction& tested_contact(CaseSpec& spec);

}  // namespace repose
