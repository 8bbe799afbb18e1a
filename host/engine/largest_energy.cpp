#include "engine/largest_energy.h"

#include <algorithm>

namespace repose {

double largest_kinetic_energy(const Simulation& sim, const std::function<bool(const gpu::vec4&)>& counted) {
  double most = 0;
  const auto& bodies = sim.rows_in_any_order(&HostState::bodies);
  if (!bodies.empty()) {
    for (const auto& b : bodies)
      if (!counted || counted(gpu::vec4(b.pos.x, b.pos.y, b.pos.z, 0.0f))) most = std::max(most, kinetic_energy_of(b).total());
    return most;
  }
  const auto& vel = sim.rows_in_any_order(&HostState::vel);
  const auto& omega = sim.rows_in_any_order(&HostState::omega);
  const auto* pos = counted ? &sim.rows_in_any_order(&HostState::pos) : nullptr;
  for (size_t i = 0; i < vel.size(); ++i)
    if (!pos || counted((*pos)[i])) most = std::max(most, kinetic_energy_of(vel[i], omega[i]).total());
  return most;
}

}  // namespace repose
