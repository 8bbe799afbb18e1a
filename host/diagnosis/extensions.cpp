#include "diagnosis/extensions.h"

#include <algorithm>
#include <stdexcept>

#include "diagnosis/elongated_body.h"

namespace repose {

Interaction& drop_interaction(CaseSpec& spec) {
  if (spec.spheres.empty()) throw std::runtime_error(spec.path + ": the case has no body to drop");
  auto plate = std::find_if(spec.walls.begin(), spec.walls.end(),
                            [](const WallSpec& w) { return w.type == WallSpec::Type::Plane; });
  if (plate == spec.walls.end()) throw std::runtime_error(spec.path + ": the case has no plane wall (plate)");
  int a = spec.spheres[0].material, b = plate->material;
  for (auto& in : spec.interactions)
    if ((in.material_a == a && in.material_b == b) || (in.material_a == b && in.material_b == a)) return in;
  throw std::runtime_error(spec.path + ": no [[interaction]] between the body and the plate");
}

const std::vector<ModelExtension>& model_extensions() {
  static const std::vector<ModelExtension> table = {
      {"restitution_velocity",
       "restitution that falls with impact speed: viscoelastic damping A Sn vn (Brilliantov et al. 1996) "
       "on top of EDEM's, 1 - e growing as v^(1/5)",
       {{"viscoelastic_time", "s", 1e-6, 3e-2, true}},
       {"rebound_height", "restitution", "height"},
       "",
       [](CaseSpec& s, const std::vector<double>& p) { drop_interaction(s).viscoelastic_time = p.at(0); }},
      {"air_drag",
       "quadratic air drag 0.5 rho C_d A v^2 on the body (A its projected area, rho = 1.2 kg/m^3)",
       {{"drag_coefficient", "1", 1e-3, 2.0, true}},  // 2: a flat plate broadside, the bluffest body
       {"rebound_height", "restitution", "height"},
       "",
       [](CaseSpec& s, const std::vector<double>& p) {
         s.air_drag.drag_coefficient = p.at(0);
         s.air_drag.air_density = 1.2;
       }},
      {"cohesion",
       "EDEM linear cohesion: an attraction k A on the contact area A = pi R* dn (moisture)",
       {{"cohesion_energy_density", "J/m^3", 1e2, 1e7, true}},
       {"rebound_height", "restitution", "height"},
       "",
       [](CaseSpec& s, const std::vector<double>& p) { drop_interaction(s).cohesion_energy_density = p.at(0); }},
      {"rolling_epsd",
       "EDEM type C elastic-plastic spring-dashpot rolling resistance",
       {},
       {},
       "needs a rolling spring per contact (a history binding) and a rolling or heap test: a drop "
       "without spin does not load rolling resistance",
       nullptr},
      {"size_spread",
       "a distribution of particle sizes instead of one size ([[fill]] radius = [min, max])",
       {},
       {},
       "shows in heaps and flows; the rebound of one sphere barely depends on its size, so drop "
       "data cannot reveal it, and diagnose does not simulate the repose rig yet",
       nullptr},
      {"shape",
       "an elongated body instead of a sphere: a chain of seven overlapping spheres of the sphere's volume, "
       "aspect ratio a (length over the central diameter); it lands at a random orientation, so its rebound "
       "scatters between replicates and falls on average",
       {{"aspect_ratio", "1", kElongatedMinAspect, kElongatedMaxAspect, false}},
       {"rebound_height", "restitution", "height"},
       "",
       [](CaseSpec& s, const std::vector<double>& p) { make_body_elongated(s, p.at(0)); },
       true},
  };
  return table;
}

const ModelExtension* find_extension(const std::string& id) {
  for (const auto& e : model_extensions())
    if (e.id == id) return &e;
  return nullptr;
}

}  // namespace repose
