#include "diagnosis/extensions.h"

#include <algorithm>
#include <stdexcept>

#include "diagnosis/bond_number.h"
#include "diagnosis/elongated_body.h"
#include "experiments/registry.h"

namespace repose {

Interaction& tested_contact(CaseSpec& spec) {
  const Experiment* e = experiment_for(spec);
  if (!e) throw std::runtime_error(spec.path + ": the case runs no experiment, so no tested contact");
  return e->tested_contact(spec);
}

const std::vector<ModelExtension>& model_extensions() {
  static const std::vector<ModelExtension> table = {
      {"restitution_velocity",
       "restitution that falls with impact speed: viscoelastic damping A Sn vn (Brilliantov et al. 1996) "
       "on top of EDEM's, 1 - e growing as v^(1/5)",
       {{"viscoelastic_time", "s", 1e-6, 3e-2, true}},
       {"rebound_height", "restitution", "height"},
       "",
       [](CaseSpec& s, const std::vector<double>& p) { tested_contact(s).viscoelastic_time = p.at(0); }},
      {"air_drag",
       "quadratic air drag 0.5 rho C_d A v^2 on the body (A its projected area, rho = 1.2 kg/m^3)",
       {{"drag_coefficient", "1", 1e-3, 2.0, true}},  // 2: a flat plate broadside, the bluffest body
       {"rebound_height", "restitution", "height", "roll_distance"},
       "",
       [](CaseSpec& s, const std::vector<double>& p) {
         s.air_drag.drag_coefficient = p.at(0);
         s.air_drag.air_density = 1.2;
       }},
      {"cohesion",
       "EDEM linear cohesion: an attraction k A on the contact area A = pi R* dn (moisture); on one body, with "
       "friction and rolling resistance on the contact's repulsion, which the attraction raises (wet contacts "
       "grip harder); between a bulk's grains, with the case's own [contact] cohesion_friction",
       {{"cohesion_energy_density", "J/m^3", 1e2, 1e7, true}},
       {"rebound_height", "restitution", "height", "slide_angle", "roll_angle", "repose_angle", "bed_height",
        "heap_height", "runout", "profile_convexity"},
       "",
       [](CaseSpec& s, const std::vector<double>& p) {
         tested_contact(s).cohesion_energy_density = p.at(0);
         // Grains of a bulk (a heap filled from [[fill]]s) are held together by the attraction
         // whatever friction sees, and the case states its engine's convention; a tilted body is
         // revealed only through the grip.
         if (s.fills.empty()) s.contact.cohesion_friction = CohesionFriction::Contact;
       },
       false,
       // In a bulk the grains' own stiffness and weight set what matters (bond_number.h): Bond
       // numbers from 1e-3 (dry as far as a heap can tell) to 3 (clods: at 2.5 slot heaps scatter
       // by 20 deg between fills, and never settle), not decades of soft-sphere nonsense.
       [](const CaseSpec& s) -> std::vector<FreeParameter> {
         if (s.fills.empty()) return {{"cohesion_energy_density", "J/m^3", 1e2, 1e7, true}};
         return {{"cohesion_energy_density", "J/m^3", heap_cohesion_for_bond_number(s, 1e-3),
                  heap_cohesion_for_bond_number(s, 3.0), true}};
       }},
      {"rolling_epsd",
       "EDEM type C rolling resistance (Ai et al. 2011 model C, LIGGGHTS epsd): a rolling spring "
       "k_r = 2.25 mu_r^2 R*^2 k_n capped at mu_r R* |Fn|, with a dashpot of rolling_damping (fraction of "
       "critical), instead of the constant torque; with spinning friction equal to each pair's rolling "
       "friction (model C has no twisting resistance: without it a grain spins on the floor forever)",
       {{"rolling_damping", "1", 0.05, 1.0, false}},
       {"repose_angle", "bed_height", "heap_height", "runout", "profile_convexity"},
       "",
       [](CaseSpec& s, const std::vector<double>& p) {
         s.contact.rolling = RollingModel::ElasticPlastic;
         s.contact.rolling_damping = p.at(0);
         // The constant torque it replaces acts on the whole spin, twist included; EPSD's spring
         // excludes the twist, so the same coefficient goes to spinning friction (a case that
         // already sets one keeps it).
         for (Interaction& in : s.interactions)
           if (in.spinning_friction == 0) in.spinning_friction = in.rolling_friction;
       }},
      {"size_spread",
       "a distribution of grain sizes instead of one size: every sphere [[fill]]'s radius uniform in "
       "[r (1 - s), r (1 + s)] about its mean r",
       {{"size_spread", "1", 0.0, 0.4, false}},
       {"repose_angle", "bed_height", "heap_height", "runout", "profile_convexity"},
       "",
       [](CaseSpec& s, const std::vector<double>& p) {
         for (FillSpec& f : s.fills) {
           if (f.template_index >= 0) continue;
           double r = 0.5 * (f.radius_min + f.radius_max);
           f.radius_min = r * (1 - p.at(0));
           f.radius_max = r * (1 + p.at(0));
         }
       }},
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
