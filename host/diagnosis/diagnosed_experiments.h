// The virtual experiments `repose diagnose` simulates, in one table: for each, the measures it
// reports and the baseline's free parameter (what calibration fits to that test):
// - drop (rebound_height, restitution, height series): the body-plate restitution;
// - repose (repose_angle, bed_height), grains from sphere [[fill]]s: the grains' sliding friction;
// - slide (slide_angle, the tilt at which the body starts to slide): the body-plate sliding friction;
// - roll, method incline (roll_distance, L on the floor): the body-plate rolling friction;
// - roll, method tilt (roll_angle, the tilt at which the body starts to roll): the same.
#pragma once
#include <string>
#include <vector>

#include "case/case_spec.h"
#include "diagnosis/extensions.h"

namespace repose {

// The smallest rolling friction a fit tries (a ball bearing): also what bounds a believable
// rolling distance when the data are read (measured_data.cpp).
constexpr double kSmallestRollingFriction = 0.002;

struct DiagnosedExperiment {
  std::string id;                      // "drop", "repose", "slide", "roll", "roll_tilt"
  std::vector<std::string> measures;   // what its rows may measure
  FreeParameter baseline;              // the baseline's free parameter and its search range
  double& (*baseline_value)(CaseSpec&);
  std::string baseline_model;          // for reports: "Hertz-Mindlin, constant restitution"
  std::string condition;               // the case key synthetic data vary by default
};

const std::vector<DiagnosedExperiment>& diagnosed_experiments();

// The entry for a case's [experiment]; nullptr when diagnose does not simulate it.
const DiagnosedExperiment* diagnosed_experiment(const CaseSpec& spec);

}  // namespace repose
