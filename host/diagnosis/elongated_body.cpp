#include "diagnosis/elongated_body.h"

#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>

#include "case/time_step.h"
#include "geometry/union_moments.h"
#include "util/math.h"

namespace repose {

namespace {
constexpr double kSideRadius = 0.7;  // side spheres, in central radii: thin enough to read as a spindle
constexpr int kSidePerEnd = 3;       // overlapping enough at a = 3 (waist 0.59 central radii)
}  // namespace

ClumpTemplate elongated_template(double a) {
  ClumpTemplate t;
  t.name = "elongated";
  t.spheres.push_back({{0, 0, 0}, 1.0});
  double tip_centre = a - kSideRadius;  // the outermost sphere reaches x = a
  for (int k = 1; k <= kSidePerEnd; ++k) {
    double x = tip_centre * k / kSidePerEnd;
    t.spheres.push_back({{x, 0, 0}, kSideRadius});
    t.spheres.push_back({{-x, 0, 0}, kSideRadius});
  }
  return t;
}

void make_body_elongated(CaseSpec& spec, double a) {
  if (spec.spheres.empty()) throw std::runtime_error(spec.path + ": shape: the case has no sphere to elongate");
  if (!(a >= kElongatedMinAspect && a <= kElongatedMaxAspect))
    throw std::runtime_error(spec.path + ": shape: aspect ratio " + std::to_string(a) + " outside [1, 3]");
  const SphereSpec sphere = spec.spheres[0];
  // The sphere's time step stays: only the shape changes (the side spheres, 0.7 of the central
  // radius, would otherwise shorten a Rayleigh-fraction step; at a = 3 the step is ~18 % of their
  // Rayleigh time for a case at 10 %, inside the 10-40 % users take).
  spec.time.dt = resolve_dt(spec);
  spec.time.rayleigh_fraction.reset();
  ClumpTemplate unit = elongated_template(a);
  // Union volume at central radius 1 (overlaps once): scale to the sphere's volume. Cached by
  // ratio: a diagnosis drops every replicate and condition of one model at the same ratio.
  static std::mutex mutex;
  static std::map<double, double> volumes;
  double v1;
  {
    std::lock_guard<std::mutex> lock(mutex);
    auto it = volumes.find(a);
    v1 = it != volumes.end() ? it->second : (volumes[a] = union_moments(unit.spheres).volume);
  }
  double rc = sphere.radius * std::cbrt(4.0 / 3.0 * kPi / v1);
  if (a == 1.0) rc = sphere.radius;  // the union is the central sphere exactly
  TemplateSpec templ;
  templ.name = "elongated";
  templ.clump = unit;
  for (Sphere& s : templ.clump.spheres) {
    s.centre *= rc;
    s.radius *= rc;
  }
  templ.where = sphere.where;
  BodySpec body;
  body.template_index = int(spec.templates.size());
  body.material = sphere.material;
  body.position = sphere.position;
  body.where = sphere.where;
  spec.templates.push_back(templ);
  spec.bodies.push_back(body);
  spec.spheres.erase(spec.spheres.begin());
}

}  // namespace repose
