// Every virtual experiment Repose runs, in one list (registry.cpp), and how the rest of the
// program finds one: by a case's [experiment] keys, or by the type a calibration plan names.
#pragma once
#include <string>
#include <vector>

#include "experiments/experiment.h"

namespace repose {

// In registry order. Several experiments may share a type (roll: incline and tilt); the first of
// a type that handles a case's keys runs it.
const std::vector<const Experiment*>& experiments();

// The experiment that runs a case (its [experiment] type, keys and contents); nullptr when none does (no
// [experiment], or an empty type).
const Experiment* experiment_for(const CaseSpec& spec);

// The experiment of `type` that handles this case (a plan names the type; its base case may have
// no [experiment] table). Throws std::runtime_error listing the types when none does.
const Experiment& experiment_of_type(const std::string& type, const CaseSpec& spec);

// The distinct types, in registry order ("drop", "slide", "roll", "repose").
std::vector<std::string> experiment_types();

// What the experiments of a type can report (the union of their responses, in order).
std::vector<std::string> responses_of_type(const std::string& type);

// Every measure a diagnosis knows (the union over the experiments it simulates).
std::vector<MeasureInfo> diagnosed_measures();

// Hands the experiments' [experiment] key readers to the case loader (case/experiment_keys.h).
// Called once at start by main() and by the test runner.
void install_experiments();

}  // namespace repose
