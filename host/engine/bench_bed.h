// The settled-bed benchmark of issue 2: N spheres of 10 mm diameter (rho 850, G 1.09 MPa,
// nu 0.32, e 0.42, mu 0.457, mu_r 0.039) in a steel box, dt = 0.2 of the Rayleigh time.
#pragma once
#include <cstdint>

#include "case/case_spec.h"

namespace repose {

// Spheres on a jittered lattice above the floor of a square box whose footprint makes the
// settled bed about half as high as it is wide; they fall and settle when simulated.
CaseSpec bench_bed_case(uint32_t n, uint64_t seed = 1);

}  // namespace repose
