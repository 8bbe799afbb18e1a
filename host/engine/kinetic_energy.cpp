#include "engine/kinetic_energy.h"

#include <algorithm>

#include "engine/simulation.h"

namespace repose {

static double squared(const gpu::vec4& v) { return double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z; }

EnergySummary kinetic_energy_of(const gpu::vec4& vel, const gpu::vec4& omega) {
  if (vel.w == 0.0f) return {};  // fixed
  return {0.5 / vel.w * squared(vel), 0.5 / omega.w * squared(omega)};
}

EnergySummary kinetic_energy_of(const gpu::Body& b) {
  if (b.pos.w == 0.0f) return {};  // fixed: infinite mass at rest
  return {0.5 / b.pos.w * squared(b.vel),
          0.5 * (double(b.omega.x) * b.ang_mom.x + double(b.omega.y) * b.ang_mom.y + double(b.omega.z) * b.ang_mom.z)};
}

EnergySummary kinetic_energy(const HostState& state) {
  EnergySummary e;
  auto add = [&e](const EnergySummary& one) {
    e.translational += one.translational;
    e.rotational += one.rotational;
  };
  if (!state.bodies.empty()) {
    for (const gpu::Body& b : state.bodies) add(kinetic_energy_of(b));
    return e;
  }
  for (size_t i = 0; i < state.vel.size(); ++i) add(kinetic_energy_of(state.vel[i], state.omega[i]));
  return e;
}

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
