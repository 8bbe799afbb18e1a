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

// A table, one row per extension: long by design (each row a few lines), nothing in it to split.
const std::vector<ModelExtension>& model_extensions() {
  static const std::vector<ModelExtension> table = {
      {.id = "restitution_velocity",
       .description = "restitution that falls with impact speed: viscoelastic damping A Sn vn (Brilliantov et al. "
                      "1996) on top of EDEM's, 1 - e growing as v^(1/5)",
       .physics = "viscoelastic_damping() in shaders/kernels/contact_law.h",
       .case_keys = "[[interaction]] viscoelastic_time of the tested contact",
       .parameters = {{"viscoelastic_time", "s", 1e-6, 3e-2, true}},
       .revealed_by = {"rebound_height", "restitution", "height"},
       .apply = [](CaseSpec& s, const std::vector<double>& p) { tested_contact(s).viscoelastic_time = p.at(0); }},
      {.id = "air_drag",
       .description = "quadratic air drag 0.5 rho C_d A v^2 on the body (A its projected area, rho = 1.2 kg/m^3)",
       .physics = "air_drag_acceleration() in shaders/kernels/kick.h",
       .case_keys = "[air_drag] drag_coefficient, air_density = 1.2",
       .parameters = {{"drag_coefficient", "1", 1e-3, 2.0, true}},  // 2: a flat plate broadside, the bluffest body
       .revealed_by = {"rebound_height", "restitution", "height", "roll_distance"},
       .apply =
           [](CaseSpec& s, const std::vector<double>& p) {
             s.air_drag.drag_coefficient = p.at(0);
             s.air_drag.air_density = 1.2;
           }},
      {.id = "cohesion",
       .description = "EDEM linear cohesion: an attraction k A on the contact area A = pi R* dn (moisture); on one "
                      "body, with friction and rolling resistance on the contact's repulsion, which the attraction "
                      "raises (wet contacts grip harder); between a bulk's grains, with the case's own [contact] "
                      "cohesion_friction",
       .physics = "linear_cohesion() and fn_grip in shaders/kernels/contact_law.h",
       .case_keys = "[[interaction]] cohesion_energy_density of the tested contact; on one body also [contact] "
                    "cohesion_friction = \"contact\"",
       .parameters = {{"cohesion_energy_density", "J/m^3", 1e2, 1e7, true}},
       .revealed_by = {"rebound_height", "restitution", "height", "slide_angle", "roll_angle", "repose_angle",
                       "bed_height", "heap_height", "runout", "profile_convexity"},
       .apply =
           [](CaseSpec& s, const std::vector<double>& p) {
             tested_contact(s).cohesion_energy_density = p.at(0);
             // Grains of a bulk (a heap filled from [[fill]]s) are held together by the attraction
             // whatever friction sees, and the case states its engine's convention; a tilted body is
             // revealed only through the grip.
             if (s.fills.empty()) s.contact.cohesion_friction = CohesionFriction::Contact;
           },
       // In a bulk the grains' own stiffness and weight set what matters (bond_number.h): Bond
       // numbers from 1e-3 (dry as far as a heap can tell) to 3 (clods: at 2.5 slot heaps scatter
       // by 20 deg between fills, and never settle), not decades of soft-sphere nonsense.
       .parameters_for = [](const CaseSpec& s) -> std::vector<FreeParameter> {
         if (s.fills.empty()) return {{"cohesion_energy_density", "J/m^3", 1e2, 1e7, true}};
         return {{"cohesion_energy_density", "J/m^3", heap_cohesion_for_bond_number(s, 1e-3),
                  heap_cohesion_for_bond_number(s, 3.0), true}};
       }},
      {.id = "rolling_epsd",
       .description = "EDEM type C rolling resistance (Ai et al. 2011 model C, LIGGGHTS epsd): a rolling spring "
                      "k_r = 2.25 mu_r^2 R*^2 k_n capped at mu_r R* |Fn|, with a dashpot of rolling_damping (fraction "
                      "of critical), instead of the constant torque; with spinning friction equal to each pair's "
                      "rolling friction (model C has no twisting resistance: without it a grain spins on the floor "
                      "forever)",
       .physics = "epsd_rolling_torque() and spinning_friction_torque() in shaders/kernels/contact_law.h",
       .case_keys = "[contact] rolling = \"epsd\", rolling_damping; [[interaction]] spinning_friction = "
                    "rolling_friction where the case sets none",
       .parameters = {{"rolling_damping", "1", 0.05, 1.0, false}},
       .revealed_by = {"repose_angle", "bed_height", "heap_height", "runout", "profile_convexity"},
       .apply =
           [](CaseSpec& s, const std::vector<double>& p) {
             s.contact.rolling = RollingModel::ElasticPlastic;
             s.contact.rolling_damping = p.at(0);
             // The constant torque it replaces acts on the whole spin, twist included; EPSD's spring
             // excludes the twist, so the same coefficient goes to spinning friction (a case that
             // already sets one keeps it).
             for (Interaction& in : s.interactions)
               if (in.spinning_friction == 0) in.spinning_friction = in.rolling_friction;
           }},
      {.id = "size_spread",
       .description = "a distribution of grain sizes instead of one size: every sphere [[fill]]'s radius uniform in "
                      "[r (1 - s), r (1 + s)] about its mean r",
       .physics = "append_fill() in host/case/particle_factory.cpp draws each radius; no kernel change",
       .case_keys = "[[fill]] radius = [min, max] of every sphere fill",
       .parameters = {{"size_spread", "1", 0.0, 0.4, false}},
       .revealed_by = {"repose_angle", "bed_height", "heap_height", "runout", "profile_convexity"},
       .apply =
           [](CaseSpec& s, const std::vector<double>& p) {
             for (FillSpec& f : s.fills) {
               if (f.template_index >= 0) continue;
               double r = 0.5 * (f.radius_min + f.radius_max);
               f.radius_min = r * (1 - p.at(0));
               f.radius_max = r * (1 + p.at(0));
             }
           }},
      {.id = "shape",
       .description = "an elongated body instead of a sphere: a chain of seven overlapping spheres of the sphere's "
                      "volume, aspect ratio a (length over the central diameter); it lands at a random orientation, "
                      "so its rebound scatters between replicates and falls on average",
       .physics = "make_body_elongated() in host/diagnosis/elongated_body.cpp (the engine's clumps)",
       .case_keys = "a [[template]] and a [[clump]] in place of the body's [[sphere]]",
       .parameters = {{"aspect_ratio", "1", kElongatedMinAspect, kElongatedMaxAspect, false}},
       .revealed_by = {"rebound_height", "restitution", "height"},
       .apply = [](CaseSpec& s, const std::vector<double>& p) { make_body_elongated(s, p.at(0)); },
       .needs_sigma = true},
  };
  return table;
}

const ModelExtension* find_extension(const std::string& id) {
  for (const auto& e : model_extensions())
    if (e.id == id) return &e;
  return nullptr;
}

}  // namespace repose
