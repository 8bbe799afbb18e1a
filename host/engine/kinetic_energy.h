// Kinetic energy: one sphere's or body's, the sum over a state, and the largest of one sphere
// or body, which the experiments wait on to call a heap or a box at rest (the studies waited
// until nothing moved).
#pragma once
#include <functional>

#include "engine/backend.h"

namespace repose {

class Simulation;

struct EnergySummary {
  double translational = 0;
  double rotational = 0;
  double total() const { return translational + rotational; }
};

// One sphere's (vel.w its 1/mass, omega.w its 1/I) and one body's; none for a fixed one (1/mass 0).
EnergySummary kinetic_energy_of(const gpu::vec4& vel, const gpu::vec4& omega);
EnergySummary kinetic_energy_of(const gpu::Body& body);

// Translational and rotational kinetic energy of the spheres, or of the bodies when there are.
EnergySummary kinetic_energy(const HostState& state);

// The largest over the spheres, or the bodies where there are clumps. `counted`, when given,
// picks the ones to count by centre (xyz; w the sphere's radius, 0 for a body). The rows are
// read in the device's order (Simulation::rows_in_any_order): a largest is the same in any order,
// and a GPU sends 32 B per sphere instead of its whole state.
double largest_kinetic_energy(const Simulation& sim, const std::function<bool(const gpu::vec4&)>& counted = {});

}  // namespace repose
