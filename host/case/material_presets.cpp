#include "case/material_presets.h"

namespace repose {

// Studies: Zheng et al., "Parameter Calibration of Cabbages (Brassica oleracea L.) Based on the
// Discrete Element Method" ("cabbage") and "Discrete Element Method for Simulation and Calibration
// of Cotton Stalk Contact Parameters" ("cotton"). Moduli converted from MPa to Pa.
const std::vector<MaterialPreset>& material_presets() {
  static const std::vector<MaterialPreset> presets = {
      {"cabbage", 850.0, 1.09e6, 0.32, "cabbage Table 1 (measured intrinsic parameters)"},
      {"q235_steel", 7850.0, 8.20e10, 0.28, "cabbage Table 2"},
      {"pvc", 1282.0, 2.00e6, 0.47, "cabbage Table 2"},
      {"eva", 79.09, 0.46e6, 0.30, "cabbage Table 2"},
      {"wood", 578.32, 0.38e8, 0.24, "cabbage Table 2"},
      {"cotton_stalk", 120.0, 1.0e6, 0.35, "cotton Table 1"},
      {"cotton_steel", 7850.0, 1.0e10, 0.30, "cotton Table 1 (steel)"},
  };
  return presets;
}

const std::vector<InteractionPreset>& interaction_presets() {
  static const std::vector<InteractionPreset> presets = {
      {"cabbage", "cabbage", 0.42, 0.457, 0.039, "cabbage Conclusions (2), calibrated"},
      {"cabbage", "q235_steel", 0.43, 0.67, 0.0476, "cabbage Conclusions (1), calibrated"},
      {"cabbage", "pvc", 0.44, 0.34, 0.0478, "cabbage Conclusions (1), calibrated"},
      {"cabbage", "eva", 0.55, 0.73, 0.0486, "cabbage Conclusions (1), calibrated"},
      {"cabbage", "wood", 0.41, 0.65, 0.0517, "cabbage Conclusions (1), calibrated"},
      {"cotton_stalk", "cotton_stalk", 0.29, 0.62, 0.02, "cotton Table 9 / Conclusions 4"},
      {"cotton_stalk", "cotton_steel", 0.44, 0.31, 0.09, "cotton Table 9 / Conclusions 4"},
  };
  return presets;
}

const MaterialPreset* find_material_preset(std::string_view name) {
  for (const auto& preset : material_presets())
    if (preset.name == name) return &preset;
  return nullptr;
}

const InteractionPreset* find_interaction_preset(std::string_view a, std::string_view b) {
  for (const auto& preset : interaction_presets())
    if ((preset.material_a == a && preset.material_b == b) ||
        (preset.material_a == b && preset.material_b == a))
      return &preset;
  return nullptr;
}

std::vector<std::string> material_preset_names() {
  std::vector<std::string> names;
  for (const auto& preset : material_presets()) names.emplace_back(preset.name);
  return names;
}

}  // namespace repose
