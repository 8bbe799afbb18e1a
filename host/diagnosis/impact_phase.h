// Drop simulations whose results vary smoothly with the model's parameters. With the coarse steps
// a diagnosis can afford (10-20 % of the Rayleigh time, 10-20 steps per contact), the depth at
// which the first contact step lands (anywhere between 0 and v dt) changes the rebound height by
// up to +-4 % (measured on cases/diagnosis/cabbage_drop.toml: 65-74 mm at H = 0.40-0.41 m), a
// jagged function no fit can follow. Shrinking dt by less than one part in the number of fall
// steps, so that the impact (free fall, with the case's quadratic air drag, solved exactly) falls
// half-way between two steps, leaves a smooth staircase of +-0.15 mm instead.
#pragma once
#include "case/case_spec.h"

namespace repose {

// Sets spec.time.dt for the case's drop test (its first sphere or its one clump, [experiment]
// drop_height).
void align_impact_phase(CaseSpec& spec);

}  // namespace repose
