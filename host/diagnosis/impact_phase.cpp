#include "diagnosis/impact_phase.h"

#include <cmath>

#include "case/time_step.h"

namespace repose {

void align_impact_phase(CaseSpec& spec) {
  if (spec.spheres.empty() && spec.bodies.empty()) return;
  constexpr double kPi = 3.14159265358979323846;
  const Vec3d& gv = spec.gravity;
  double g = std::sqrt(gv[0] * gv[0] + gv[1] * gv[1] + gv[2] * gv[2]);
  double H = spec.experiment.drop_height;
  if (!(g > 0) || !(H > 0)) return;
  // Fall from rest under gravity and drag k v^2 (per unit mass): t = acosh(exp(k H)) / sqrt(g k).
  // A clump body falls in vacuum (the engine's drag acts on free spheres only) and without
  // turning, so its lowest point meets the plate after sqrt(2 H / g) whatever its orientation.
  double k = 0;
  if (!spec.spheres.empty()) {
    const SphereSpec& body = spec.spheres[0];
    double r = body.radius;
    double mass = spec.materials.at(body.material).density * 4.0 / 3.0 * kPi * r * r * r;
    k = 0.5 * spec.air_drag.air_density * spec.air_drag.drag_coefficient * kPi * r * r / mass;
  }
  double t_impact = k * H > 1e-9 ? std::acosh(std::exp(k * H)) / std::sqrt(g * k) : std::sqrt(2 * H / g);
  double dt = resolve_dt(spec);
  double steps = std::floor(t_impact / dt);
  if (steps < 10) return;  // a step that long is not a drop simulation anyway
  spec.time.dt = t_impact / (steps + 0.5);
  spec.time.rayleigh_fraction.reset();
}

}  // namespace repose
