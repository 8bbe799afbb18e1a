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

namespace repose {

struct FreeParameter {
  std::string name;  // as reported, e.g. "drag_coefficient"
  std::string unit;
  double lo = 0, hi = 1;  // search range
  bool log_scale = false; // search log(value) (strengths spanning decades)
};

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

// The interaction between a drop, tilt or roll case's body (its first sphere, else its first
// clump) and its plate (a drop's first plane wall; a tilt or roll test's [experiment] plate,
// default the first wall): the contact those tests calibrate and the extensions act on. Throws
// naming the case when absent.
Interaction& body_plate_interaction(CaseSpec& spec);

// The grains' contact with each other in a heap case: the first [[fill]]'s material with itself.
// Throws naming the case when absent.
Interaction& heap_interaction(CaseSpec& spec);

}  // namespace repose
