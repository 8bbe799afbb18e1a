// A case file's [[material]] and [[interaction]] entries, and the check that every pair of
// materials that can touch has its interaction.
#include "case/case_reader.h"

#include <algorithm>

#include "case/case_error.h"
#include "case/material_presets.h"
#include "case/physical_ranges.h"
#include "case/spelling.h"

namespace repose {

void CaseReader::read_material(const Section& s) {
  s.allow_only({"name", "preset", "density", "shear_modulus", "youngs_modulus", "poisson"}, "a [[material]]");
  Material m;
  m.where = s.where();
  const MaterialPreset* preset = nullptr;
  if (auto preset_name = s.text("preset")) {
    preset = find_material_preset(*preset_name);
    if (!preset)
      s.fail("preset", "unknown preset '" + *preset_name + "'" +
                           did_you_mean(*preset_name, material_preset_names()) +
                           " (presets: " + quoted_list(material_preset_names()) + ")");
  }
  if (auto name = s.text("name")) m.name = *name;
  else if (preset) m.name = std::string(preset->name);
  else s.missing("name", " (or give a preset)");
  if (!usable_name(m.name))
    s.fail(s.has("name") ? "name" : "preset",
           "'" + m.name + "' is not a usable name: letters, digits, '_' and '-', starting with a letter or '_'");
  for (const Material& other : spec_.materials)
    if (other.name == m.name)
      s.fail(s.has("name") ? "name" : "preset",
             "material '" + m.name + "' is already defined at line " + std::to_string(other.where.line));

  m.density = s.number("density").value_or(preset ? preset->density : 0);
  if (!s.has("density") && !preset) s.missing("density", " (kg/m^3)");
  positive(s, "density", m.density);

  m.poisson = s.number("poisson").value_or(preset ? preset->poisson : 0);
  if (!s.has("poisson") && !preset) s.missing("poisson", " (Poisson's ratio)");
  if (!(m.poisson > -1 && m.poisson < 0.5))
    s.fail("poisson", format_number(m.poisson) + " is outside (-1, 0.5)");

  if (s.has("shear_modulus") && s.has("youngs_modulus"))
    s.fail(line_of(*s.table().get("shear_modulus")) > line_of(*s.table().get("youngs_modulus"))
               ? "shear_modulus" : "youngs_modulus",
           "give shear_modulus or youngs_modulus, not both");
  if (auto g = s.number("shear_modulus")) {
    m.shear_modulus = positive(s, "shear_modulus", *g);
    m.youngs_modulus = 2 * m.shear_modulus * (1 + m.poisson);
  } else if (auto e = s.number("youngs_modulus")) {
    m.youngs_modulus = positive(s, "youngs_modulus", *e);
    m.shear_modulus = m.youngs_modulus / (2 * (1 + m.poisson));
  } else if (preset) {
    m.shear_modulus = preset->shear_modulus;
    m.youngs_modulus = 2 * m.shear_modulus * (1 + m.poisson);
  } else {
    s.missing("shear_modulus", ": give shear_modulus or youngs_modulus (Pa)");
  }
  auto where_of = [&](std::initializer_list<const char*> keys) {
    for (const char* k : keys)
      if (s.has(k)) return s.where(k);
    return s.where();
  };
  check_density(m.density, where_of({"density", "preset"}), spec_.warnings);
  check_shear_modulus(m.shear_modulus, where_of({"shear_modulus", "youngs_modulus", "preset"}), spec_.warnings);
  spec_.materials.push_back(m);
}

std::vector<std::string> CaseReader::material_names() const {
  std::vector<std::string> names;
  for (const Material& m : spec_.materials) names.push_back(m.name);
  return names;
}

int CaseReader::material_index(const Section& s, std::string_view k, const std::string& name) const {
  for (size_t i = 0; i < spec_.materials.size(); ++i)
    if (spec_.materials[i].name == name) return int(i);
  s.fail(k, "unknown material '" + name + "'" + did_you_mean(name, material_names()) +
                " (materials: " + quoted_list(material_names()) + ")");
}

int CaseReader::material_of(const Section& s) const {
  return material_index(s, "material", s.required_text("material", " (a [[material]] name)"));
}

// Exactly two strings: ["a", "b"].
std::pair<std::string, std::string> CaseReader::name_pair(const Section& s, std::string_view k) const {
  const toml::node* node = s.table().get(k);
  const toml::array* array = node ? node->as_array() : nullptr;
  if (!array || array->size() != 2 || !array->get(0)->is_string() || !array->get(1)->is_string())
    s.fail(k, "expected two names, as [\"a\", \"b\"]");
  return {array->get(0)->as_string()->get(), array->get(1)->as_string()->get()};
}

void CaseReader::read_interaction(const Section& s) {
  std::vector<std::string> keys{"materials", "preset", "restitution", "static_friction", "rolling_friction"};
#define REPOSE_INTERACTION_KEY(name, fallback, check) keys.push_back(#name);
  REPOSE_INTERACTION_OPTIONS(REPOSE_INTERACTION_KEY)
#undef REPOSE_INTERACTION_KEY
  s.allow_only(keys, "an [[interaction]]");
  Interaction in;
  in.where = s.where();
  if (!s.has("materials")) s.missing("materials", " (two material names, as [\"a\", \"b\"])");
  auto [a, b] = name_pair(s, "materials");
  in.material_a = material_index(s, "materials", a);
  in.material_b = material_index(s, "materials", b);
  for (const Interaction& other : spec_.interactions)
    if ((other.material_a == in.material_a && other.material_b == in.material_b) ||
        (other.material_a == in.material_b && other.material_b == in.material_a))
      s.fail("materials", "duplicate interaction: '" + a + "' and '" + b + "' already have one at line " +
                              std::to_string(other.where.line));

  const InteractionPreset* preset = nullptr;
  if (s.has("preset")) {
    auto [pa, pb] = name_pair(s, "preset");
    preset = find_interaction_preset(pa, pb);
    if (!preset) {
      std::vector<std::string> known;
      for (const auto& p : interaction_presets())
        known.push_back("[\"" + std::string(p.material_a) + "\", \"" + std::string(p.material_b) + "\"]");
      std::string presets;
      for (const auto& k : known) presets += (presets.empty() ? "" : ", ") + k;
      s.fail("preset", "no interaction preset for '" + pa + "' and '" + pb + "' (presets: " + presets + ")");
    }
  }
  auto parameter = [&](const char* k, double preset_value) {
    if (auto value = s.number(k)) return *value;
    if (!preset) s.missing(k);
    return preset_value;
  };
  in.restitution = parameter("restitution", preset ? preset->restitution : 0);
  if (!(in.restitution > 0 && in.restitution <= 1))
    s.fail("restitution", format_number(in.restitution) + " is outside (0, 1]");
  in.static_friction = parameter("static_friction", preset ? preset->static_friction : 0);
  if (in.static_friction < 0) s.fail("static_friction", format_number(in.static_friction) + " must not be negative");
  in.rolling_friction = parameter("rolling_friction", preset ? preset->rolling_friction : 0);
  if (in.rolling_friction < 0)
    s.fail("rolling_friction", format_number(in.rolling_friction) + " must not be negative");
  // The optional keys (REPOSE_INTERACTION_OPTIONS), their defaults unless given.
#define REPOSE_READ_NonNegative(name) \
  if (auto v = s.number(#name)) in.name = non_negative(s, #name, *v);
#define REPOSE_READ_Switch(name) \
  if (auto v = s.boolean(#name)) in.name = *v ? 1.0 : 0.0;
#define REPOSE_READ_OPTION(name, fallback, check) REPOSE_READ_##check(name)
  REPOSE_INTERACTION_OPTIONS(REPOSE_READ_OPTION)
#undef REPOSE_READ_OPTION
#undef REPOSE_READ_Switch
#undef REPOSE_READ_NonNegative
  spec_.interactions.push_back(in);
}

// Remembers the first entry that puts a material among the particles or on a wall, so that a
// missing [[interaction]] can be reported where the pair first meets.
void CaseReader::note_use(std::map<int, SourceRef>& users, int material, const Section& s) {
  users.emplace(material, s.where("material"));
}

// Every pair of materials that can touch (particle-particle, particle-wall) needs its
// contact parameters: there is no sensible default for restitution or friction.
void CaseReader::check_interactions_cover_use() {
  auto covered = [&](int a, int b) {
    return std::any_of(spec_.interactions.begin(), spec_.interactions.end(), [&](const Interaction& in) {
      return (in.material_a == a && in.material_b == b) || (in.material_a == b && in.material_b == a);
    });
  };
  auto report = [&](const SourceRef& first, const SourceRef& second, int a, int b) {
    const SourceRef& later = first.line >= second.line ? first : second;
    const SourceRef& earlier = first.line >= second.line ? second : first;
    std::string name_a = spec_.materials[size_t(a)].name, name_b = spec_.materials[size_t(b)].name;
    std::string meeting = a == b ? "particles of '" + name_a + "' touch each other"
                                 : "'" + name_a + "' meets '" + name_b + "' (" + earlier.key + ", line " +
                                       std::to_string(earlier.line) + ")";
    throw CaseError(later, meeting + " but no [[interaction]] gives materials = [\"" + name_a + "\", \"" +
                               name_b + "\"] its restitution and friction");
  };
  for (auto i = particle_users_.begin(); i != particle_users_.end(); ++i)
    for (auto j = i; j != particle_users_.end(); ++j) {
      bool can_meet = i != j || particles_of(i->first) > 1;  // one lone sphere meets no twin
      if (can_meet && !covered(i->first, j->first)) report(i->second, j->second, i->first, j->first);
    }
  for (const auto& [particle, particle_ref] : particle_users_)
    for (const auto& [wall, wall_ref] : wall_users_)
      if (!covered(particle, wall)) report(particle_ref, wall_ref, particle, wall);
}

}  // namespace repose
