// The candidate model extensions of `repose diagnose` (docs/diagnosis.md): what each adds to the
// baseline Hertz-Mindlin model, its parameters with their search ranges, and how it is switched
// on in a case. This table is the one place to add another candidate: give it an id, its
// parameters and an `apply` that writes them into a CaseSpec (and the physics, off by default,
// in the kernels), and diagnose fits and compares it with the rest.
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
  std::vector<FreeParameter> parameters;
  // Which measures can reveal it; empty: none of the experiments diagnose runs yet (pending).
  std::vector<std::string> revealed_by;
  std::string pending_reason;  // why it cannot be tested yet, when revealed_by is empty
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
