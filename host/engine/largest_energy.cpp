#include "engine/largest_energy.h"

#include <algorithm>

namespace repose {

static double squared(const gpu::vec4& v) { return double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z; }

double largest_kinetic_energy(const Simulation& sim, const std::function<bool(const gpu::vec4&)>& counted) {
  double most = 0;
  const auto& bodies = sim.rows_in_any_order(&HostState::bodies);
  if (!bodies.empty()) {
    for (const auto& b : bodies) {
      if (b.pos.w == 0.0f || (counted && !counted(gpu::vec4(b.pos.x, b.pos.y, b.pos.z, 0.0f)))) continue;
      double rot = double(b.omega.x) * b.ang_mom.x + double(b.omega.y) * b.ang_mom.y + double(b.omega.z) * b.ang_mom.z;
      most = std::max(most, 0.5 / b.pos.w * squared(b.vel) + 0.5 * rot);  // pos.w: 1/mass
    }
    return most;
  }
  const auto& vel = sim.rows_in_any_order(&HostState::vel);  // w: 1/mass (0: fixed)
  const auto& omega = sim.rows_in_any_order(&HostState::omega);  // w: 1/I
  const auto* pos = counted ? &sim.rows_in_any_order(&HostState::pos) : nullptr;
  for (size_t i = 0; i < vel.size(); ++i)
    if (vel[i].w != 0.0f && (!pos || counted((*pos)[i])))
      most = std::max(most, 0.5 / vel[i].w * squared(vel[i]) + 0.5 / omega[i].w * squared(omega[i]));
  return most;
}

}  // namespace repose
