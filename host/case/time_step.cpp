#include "case/time_step.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "case/case_error.h"
#include "util/math.h"

namespace repose {

double rayleigh_time(double radius, const Material& material) {
  return kPi * radius * std::sqrt(material.density / material.shear_modulus) /
         (0.1631 * material.poisson + 0.8766);
}

RayleighLimit rayleigh_limit(const CaseSpec& spec) {
  RayleighLimit limit;
  limit.time = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < spec.spheres.size(); ++i) {
    const SphereSpec& sphere = spec.spheres[i];
    double time = rayleigh_time(sphere.radius, spec.materials.at(size_t(sphere.material)));
    if (time < limit.time) {
      limit.time = time;
      limit.sphere = int(i);
      limit.radius = sphere.radius;
      limit.material = sphere.material;
      limit.where = sphere.where;
    }
  }
  for (size_t b = 0; b < spec.bodies.size(); ++b) {
    const BodySpec& body = spec.bodies[b];
    double smallest = 1e300;
    for (const Sphere& s : spec.templates.at(size_t(body.template_index)).clump.spheres)
      smallest = std::min(smallest, s.radius * body.scale);
    double time = rayleigh_time(smallest, spec.materials.at(size_t(body.material)));
    if (time < limit.time) {
      limit = RayleighLimit{time, -1, int(b), smallest, body.material, body.where};
    }
  }
  return limit;
}

double rayleigh_time(const CaseSpec& spec) { return rayleigh_limit(spec).time; }

double resolve_dt(const CaseSpec& spec) {
  const TimeSpec& time = spec.time;
  if (time.dt.has_value() == time.rayleigh_fraction.has_value())
    throw CaseError(time.where, "give exactly one of dt and rayleigh_fraction");
  if (time.dt) return *time.dt;
  if (spec.spheres.empty() && spec.bodies.empty())
    throw CaseError(time.where, "rayleigh_fraction needs at least one sphere to measure");
  return *time.rayleigh_fraction * rayleigh_time(spec);
}

}  // namespace repose
