#include "diagnosis/bond_number.h"

#include <cmath>
#include <stdexcept>

#include "util/math.h"

namespace repose {

namespace {


struct Grain {
  double radius_star, e_star, weight;
};

Grain heap_grain(const CaseSpec& spec) {
  if (spec.fills.empty()) throw std::runtime_error(spec.path + ": the case has no [[fill]] of grains");
  const FillSpec& f = spec.fills[0];
  const Material& m = spec.materials.at(size_t(f.material));
  double r = 0.5 * (f.radius_min + f.radius_max);
  double g = std::sqrt(spec.gravity[0] * spec.gravity[0] + spec.gravity[1] * spec.gravity[1] +
                       spec.gravity[2] * spec.gravity[2]);
  double e = m.youngs_modulus > 0 ? m.youngs_modulus : 2 * m.shear_modulus * (1 + m.poisson);
  return {0.5 * r, e / (2 * (1 - m.poisson * m.poisson)), m.density * g * 4.0 / 3.0 * kPi * r * r * r};
}

}  // namespace

double heap_bond_number(const CaseSpec& spec, double k) {
  Grain gr = heap_grain(spec);
  double hertz = 4.0 / 3.0 * gr.e_star * std::sqrt(gr.radius_star);
  double pull = k * kPi * gr.radius_star;
  return 4.0 / 27.0 * pull * pull * pull / (hertz * hertz) / gr.weight;
}

double heap_cohesion_for_bond_number(const CaseSpec& spec, double bond) {
  Grain gr = heap_grain(spec);
  double hertz = 4.0 / 3.0 * gr.e_star * std::sqrt(gr.radius_star);
  return std::cbrt(27.0 / 4.0 * bond * gr.weight * hertz * hertz) / (kPi * gr.radius_star);
}

}  // namespace repose
