// What replicates of a one-body experiment share (`repose experiment --replicates N`): replicate k
// runs the case with simulation.seed + k, its clump at a random orientation drawn from that seed,
// and the replicates' values are summarised by their mean and sample standard deviation.
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include "case/case_spec.h"

namespace repose {

// Mean and sample standard deviation (0 for fewer than two values).
std::pair<double, double> mean_sd(const std::vector<double>& x);

// Turns the case's first clump that is not fixed to a random orientation drawn from `seed`
// (uniform over rotations); a case without such a clump is left as it is.
void random_body_orientation(CaseSpec& spec, uint64_t seed);

}  // namespace repose
