// The largest kinetic energy of one free sphere or body: what the experiments wait on to call a
// heap or a box at rest (the studies waited until nothing moved).
#pragma once
#include <functional>

#include "engine/simulation.h"

namespace repose {

// Over the spheres, or the bodies where there are clumps; fixed ones never move. `counted`, when
// given, picks the ones to count by centre (xyz; w the sphere's radius, 0 for a body). The rows are
// read in the device's order (Simulation::rows_in_any_order): a largest is the same in any order,
// and a GPU sends 32 B per sphere instead of its whole state.
double largest_kinetic_energy(const Simulation& sim, const std::function<bool(const gpu::vec4&)>& counted = {});

}  // namespace repose
