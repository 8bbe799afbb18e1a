// Materials and contact parameters measured or calibrated in the two studies, by name, so a
// case can say `preset = "cabbage"` instead of copying numbers (and override any one of them).
#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace repose {

struct MaterialPreset {
  std::string_view name;
  double density;        // kg/m^3
  double shear_modulus;  // Pa
  double poisson;
  std::string_view source;  // the study's table the values come from
};

// An [[interaction]] preset: the calibrated contact parameters between two preset materials.
struct InteractionPreset {
  std::string_view material_a, material_b;
  double restitution;
  double static_friction;
  double rolling_friction;
  std::string_view source;
};

const std::vector<MaterialPreset>& material_presets();
const std::vector<InteractionPreset>& interaction_presets();

// nullptr when there is no such preset.
const MaterialPreset* find_material_preset(std::string_view name);
// Either order of the two names.
const InteractionPreset* find_interaction_preset(std::string_view a, std::string_view b);

std::vector<std::string> material_preset_names();

}  // namespace repose
