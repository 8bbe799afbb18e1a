// The granular Bond number of a heap's grains under EDEM linear cohesion (an attraction k pi R* dn
// on a Hertz contact): the pull-off force of two grains over one grain's weight. The net
// attraction k pi R* dn - 4/3 E* sqrt(R*) dn^(3/2) peaks at dn = (2 k pi R* / (2 E* sqrt R*))^2,
// where it is (4/27) (k pi R*)^3 / (4/3 E* sqrt R*)^2: the largest pull a contact holds before the
// grains part. Bo << 1 leaves a heap as dry grains make it; of order one, cohesion shapes its flow
// and its slope; well above, grains move as clods. The diagnosis searches a heap's cohesion over
// Bond numbers 1e-3 to 3 of the case's grains and reports the Bond number of what it fits.
#pragma once
#include "case/case_spec.h"

namespace repose {

// For the first [[fill]]'s grains (material with itself, mean radius) under the case's gravity.
// Throws std::runtime_error naming the case when it has no fill or no such material.
double heap_bond_number(const CaseSpec& spec, double cohesion_energy_density);
double heap_cohesion_for_bond_number(const CaseSpec& spec, double bond_number);

}  // namespace repose
