#include "case/case_loader.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "case/body_pose.h"
#include "case/case_override.h"
#include "case/experiment_keys.h"
#include "case/material_presets.h"
#include "case/particle_factory.h"
#include "case/physical_ranges.h"
#include "case/spelling.h"
#include "case/toml_section.h"
#include "case/time_step.h"
#include "geometry/sphere_csv.h"
#include "geometry/stl.h"
#include "geometry/templates.h"
#include "util/hash.h"
#include "util/path_name.h"
#include "util/input_file.h"

namespace repose {
namespace {

// Names usable in override keys ("material.cabbage.density"): no dots, no slashes, and not all
// digits (those are indices).
bool usable_name(const std::string& name) {
  if (name.empty() || !(std::isalpha((unsigned char)name[0]) || name[0] == '_')) return false;
  return std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '_' || c == '-';
  });
}

class CaseReader {
 public:
  CaseReader(const toml::table& root, const std::string& path) : root_(root), file_(path) {}

  CaseSpec read() {
    spec_.identity = toml_identity(root_);
    Section top(root_, "", file_);
    top.allow_only({"simulation", "contact", "neighbour", "output", "experiment", "air_drag", "material",
                    "interaction", "template", "sphere", "clump", "fill", "lattice", "wall"},
                   "the case file");
    spec_.path = file_;
    read_simulation();
    read_contact();
    read_neighbour();
    read_output();
    read_experiment();
    read_air_drag();
    for (const Section& s : entries("material")) read_material(s);
    if (spec_.materials.empty())
      throw CaseError({file_, "material", 0}, "the case has no [[material]]");
    for (const Section& s : entries("interaction")) read_interaction(s);
    for (const Section& s : entries("template")) read_template(s);
    for (const Section& s : entries("sphere")) read_sphere(s);
    for (const Section& s : entries("clump")) read_clump(s);
    int fill_index = 0;
    for (const Section& s : entries("fill")) read_fill(s, fill_index++);
    for (const Section& s : entries("lattice")) read_lattice(s);
    int wall_index = 0;
    for (const Section& s : entries("wall")) read_wall(s, wall_index++);
    check_experiment_walls();
    if (spec_.spheres.empty() && spec_.bodies.empty() && spec_.fills.empty() && spec_.lattices.empty())
      throw CaseError({file_, "", 0}, "the case has no particles: add [[sphere]], [[clump]], [[fill]] or [[lattice]]");
    check_interactions_cover_use();
    expand_particles(spec_);
    check_time_step();
    check_case_ranges(spec_);
    return std::move(spec_);
  }

 private:
  // The parsed document as sorted "dotted.key = value" lines ("material.0.density = 850"),
  // numbers in their shortest exact form: no comments or layout of the source.
  static std::string toml_identity(const toml::table& root) {
    std::string lines;
    flatten(root, "", lines);
    return lines;
  }

  static std::string value_text(const toml::node& node) {
    if (auto a = node.as_array()) {
      std::string text = "[";
      for (size_t k = 0; k < a->size(); ++k) text += (k ? ", " : "") + value_text(*a->get(k));
      return text + "]";
    }
    if (auto t = node.as_table()) {
      std::string text;
      flatten(*t, "", text);
      return "{" + text + "}";
    }
    if (node.is_floating_point()) return shortest_number(node.as_floating_point()->get());
    std::ostringstream text;
    text << toml::toml_formatter(node, toml::format_flags::none);
    return text.str();
  }

  static void flatten(const toml::table& table, const std::string& prefix, std::string& lines) {
    for (const auto& [key, node] : table) {
      std::string path = prefix + std::string(key.str());
      if (auto t = node.as_table()) {
        flatten(*t, path + ".", lines);
      } else if (auto a = node.as_array(); a && a->is_array_of_tables()) {
        for (size_t k = 0; k < a->size(); ++k) flatten(*a->get(k)->as_table(), path + "." + std::to_string(k) + ".", lines);
      } else {
        lines += path + " = " + value_text(node) + "\n";
      }
    }
  }

  static std::string shortest_number(double v) {
    char text[32];
    for (int digits = 1; digits <= 17; ++digits) {
      std::snprintf(text, sizeof text, "%.*g", digits, v);
      if (std::strtod(text, nullptr) == v) break;
    }
    return text;
  }

  // A file the case reads goes into its identity by content, so an edited template or mesh is
  // a different case (a campaign does not mix two geometries).
  void note_input_file(const std::string& as_written, const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    spec_.identity += "# file " + as_written + " fnv1a " + fnv1a_hex(bytes.str()) + "\n";
  }

  // The elements of an array of tables ([[material]] ...), each as a Section "material[i]".
  std::vector<Section> entries(const std::string& name) {
    std::vector<Section> sections;
    const toml::node* node = root_.get(name);
    if (!node) return sections;
    Section top(root_, "", file_);
    if (node->is_table())
      top.fail(name, "write [[" + name + "]] (one entry of a list), not [" + name + "]");
    if (!node->is_array()) top.wrong_type(name, "[[" + name + "]] entries");
    const toml::array& array = *node->as_array();
    for (size_t i = 0; i < array.size(); ++i) {
      std::string prefix = name + "[" + std::to_string(i) + "]";
      if (!array.get(i)->is_table())
        throw CaseError({file_, prefix, line_of(*array.get(i))},
                        std::string("expected a table, got ") + type_name(*array.get(i)));
      sections.emplace_back(*array.get(i)->as_table(), prefix, file_);
    }
    return sections;
  }

  std::optional<Section> table(const std::string& name) {
    return Section(root_, "", file_).sub(name);
  }

  void read_simulation() {
    auto s = table("simulation");
    if (!s)
      throw CaseError({file_, "simulation", 0},
                      "missing [simulation] table (end_time and dt or rayleigh_fraction are required)");
    s->allow_only({"name", "seed", "end_time", "dt", "rayleigh_fraction", "gravity", "integrator"},
                  "[simulation]");
    spec_.name = s->text("name").value_or(std::filesystem::path(file_).stem().string());
    // The name becomes file and folder names (frames/NAME_00000.vtp, out/NAME): it must stay inside.
    if (std::string why = why_not_path_name(spec_.name); !why.empty()) {
      if (s->has("name")) s->fail("name", why);
      throw CaseError({file_, "simulation.name", 0}, "the case file's name gives the case no usable name (" + why +
                                                         "): give simulation.name");
    }
    if (auto seed = s->integer("seed")) {
      if (*seed < 0) s->fail("seed", "must not be negative");
      spec_.seed = uint64_t(*seed);
    }
    spec_.gravity = s->vector3("gravity").value_or(spec_.gravity);
    double g = std::sqrt(spec_.gravity[0] * spec_.gravity[0] + spec_.gravity[1] * spec_.gravity[1] +
                         spec_.gravity[2] * spec_.gravity[2]);
    if (!(g <= 1e4))  // a geotechnical centrifuge reaches a few hundred g
      s->fail("gravity", "|gravity| = " + format_number(g) + " m/s^2 is " + format_number(g / 9.81) +
                             " g: more than 1e4 m/s^2 is no lab, planet or centrifuge (a unit slip?)");
    spec_.integrator = s->choice<Integrator>(
        "integrator",
        {{"velocity_verlet", Integrator::VelocityVerlet}, {"symplectic_euler", Integrator::SymplecticEuler}},
        Integrator::VelocityVerlet);

    TimeSpec& time = spec_.time;
    time.end_time = s->required_number("end_time", " (simulated time in s)");
    time.end_where = s->where("end_time");
    if (!(time.end_time > 0)) s->fail("end_time", format_number(time.end_time) + " must be greater than 0");
    bool has_dt = s->has("dt"), has_fraction = s->has("rayleigh_fraction");
    if (has_dt && has_fraction) {
      const char* later = line_of(*s->table().get("dt")) > line_of(*s->table().get("rayleigh_fraction"))
                              ? "dt" : "rayleigh_fraction";
      s->fail(later, "give dt or rayleigh_fraction, not both");
    }
    if (!has_dt && !has_fraction)
      s->missing("dt", ": give dt (time step in s) or rayleigh_fraction (of the Rayleigh time)");
    if (has_dt) {
      time.dt = positive(*s, "dt", *s->number("dt"));
      time.where = s->where("dt");
    } else {
      double fraction = positive(*s, "rayleigh_fraction", *s->number("rayleigh_fraction"));
      if (fraction > 1)
        s->fail("rayleigh_fraction", format_number(fraction) +
                                         " is above 1: a step longer than the Rayleigh time is unstable "
                                         "(0.1 to 0.4 is usual)");
      time.rayleigh_fraction = fraction;
      time.where = s->where("rayleigh_fraction");
    }
  }

  void read_contact() {
    auto s = table("contact");
    if (!s) return;
    s->allow_only({"coulomb_cap", "normal_attraction", "rolling", "rolling_omega", "rolling_lever", "rolling_damping",
                   "cohesion_friction", "cohesion_area"},
                  "[contact]");
    ContactOptions& c = spec_.contact;
    c.coulomb_cap = s->choice<CoulombCap>(
        "coulomb_cap", {{"spring_and_damper", CoulombCap::SpringAndDamper}, {"spring", CoulombCap::SpringOnly}},
        c.coulomb_cap);
    c.normal_attraction = s->choice<NormalAttraction>(
        "normal_attraction", {{"allow", NormalAttraction::Allow}, {"clip", NormalAttraction::Clip}},
        c.normal_attraction);
    c.rolling = s->choice<RollingModel>(
        "rolling",
        {{"constant_torque", RollingModel::ConstantTorque}, {"none", RollingModel::None}, {"epsd", RollingModel::ElasticPlastic}},
        c.rolling);
    c.rolling_omega = s->choice<RollingOmega>(
        "rolling_omega", {{"own", RollingOmega::Own}, {"relative", RollingOmega::Relative}}, c.rolling_omega);
    // LIGGGHTS's relative torque takes R* of the touching spheres: its lever is the sphere's.
    RollingLever lever_default =
        c.rolling_omega == RollingOmega::Relative ? RollingLever::Sphere : c.rolling_lever;
    c.rolling_lever = s->choice<RollingLever>(
        "rolling_lever", {{"centre", RollingLever::Centre}, {"sphere", RollingLever::Sphere}}, lever_default);
    if (c.rolling_omega == RollingOmega::Relative && c.rolling_lever == RollingLever::Centre)
      s->fail("rolling_lever", "\"centre\" belongs to EDEM's torque against each body's own spin; "
                               "rolling_omega = \"relative\" (LIGGGHTS cdt) takes R* of the touching spheres");
    c.cohesion_friction = s->choice<CohesionFriction>(
        "cohesion_friction", {{"net", CohesionFriction::Net}, {"contact", CohesionFriction::Contact}},
        c.cohesion_friction);
    c.cohesion_area = s->choice<CohesionArea>(
        "cohesion_area", {{"hertz", CohesionArea::Hertz}, {"intersection", CohesionArea::Intersection}},
        c.cohesion_area);
    if (auto eta = s->number("rolling_damping")) {
      c.rolling_damping = non_negative(*s, "rolling_damping", *eta);
      if (c.rolling != RollingModel::ElasticPlastic)
        s->fail("rolling_damping", "applies to rolling = \"epsd\" only (the constant torque has no dashpot)");
    }
    if (c.rolling == RollingModel::ElasticPlastic && c.rolling_omega == RollingOmega::Relative)
      s->fail("rolling_omega", "\"relative\" belongs to the constant torque; the EPSD spring always acts on the "
                               "relative rolling rotation");
  }

  void read_neighbour() {
    auto s = table("neighbour");
    if (!s) return;
    s->allow_only({"skin", "rebuild_interval"}, "[neighbour]");
    if (auto skin = s->number("skin")) spec_.neighbour.skin = non_negative(*s, "skin", *skin);
    if (auto interval = s->integer("rebuild_interval")) {
      if (*interval < 0 || *interval > 1000000) s->fail("rebuild_interval", "must be 0 (automatic) or a number of steps");
      spec_.neighbour.rebuild_interval = int(*interval);
    }
  }

  void read_output() {
    auto s = table("output");
    if (!s) return;
    s->allow_only({"interval", "vtk", "checkpoint_interval"}, "[output]");
    if (auto interval = s->number("interval")) spec_.output.interval = non_negative(*s, "interval", *interval);
    if (auto every = s->number("checkpoint_interval"))
      spec_.output.checkpoint_interval = non_negative(*s, "checkpoint_interval", *every);
    spec_.output.vtk = s->boolean("vtk").value_or(spec_.output.vtk);
  }

  // [experiment]: its type picks the experiment that reads the rest (case/experiment_keys.h).
  void read_experiment() {
    auto s = table("experiment");
    if (!s) return;
    ExperimentSpec& ex = spec_.experiment;
    const auto& readers = experiment_key_readers();
    if (readers.empty())
      s->fail("the program has not installed the experiments that read [experiment] (install_experiments())");
    std::vector<std::string> types;
    for (const auto& r : readers) types.push_back(r.type);
    std::string listed;
    for (size_t k = 0; k < types.size(); ++k)
      listed += (k == 0 ? "" : k + 1 == types.size() ? " or " : ", ") + types[k];
    std::string type = s->required_text("type", " (" + listed + ")");
    auto reader = std::find_if(readers.begin(), readers.end(), [&](const auto& r) { return r.type == type; });
    if (reader == readers.end())
      s->fail("type", "unknown experiment '" + type + "' (" + listed + ")" + did_you_mean(type, types));
    ex.type = type;
    std::vector<std::string> allowed{"type", "max_time"};
    allowed.insert(allowed.end(), reader->keys.begin(), reader->keys.end());
    s->allow_only(allowed, "[experiment] of type '" + type + "'");
    ex.where = s->where();
    if (auto t = s->number("max_time")) ex.max_time = positive(*s, "max_time", *t);
    reader->read(*s, ex);
  }

  // [experiment] names walls; they must exist (checked once all walls are read).
  void check_experiment_walls() {
    const ExperimentSpec& ex = spec_.experiment;
    auto exists = [&](const std::string& name) {
      return std::any_of(spec_.walls.begin(), spec_.walls.end(), [&](const WallSpec& w) { return w.name == name; });
    };
    std::vector<std::string> names;
    for (const WallSpec& w : spec_.walls) names.push_back(w.name);
    for (const auto& [key, name] : {std::pair<std::string, std::string>{"plate", ex.plate}, {"lift_wall", ex.lift_wall}})
      if (!name.empty() && !exists(name))
        throw CaseError({file_, "experiment." + key, ex.where.line},
                        "no [[wall]] is named '" + name + "'" + did_you_mean(name, names));
  }

  // Extension air_drag (docs/diagnosis.md).
  void read_air_drag() {
    auto s = table("air_drag");
    if (!s) return;
    s->allow_only({"drag_coefficient", "air_density"}, "[air_drag]");
    spec_.air_drag.where = s->where();
    if (auto cd = s->number("drag_coefficient"))
      spec_.air_drag.drag_coefficient = non_negative(*s, "drag_coefficient", *cd);
    if (auto rho = s->number("air_density")) spec_.air_drag.air_density = positive(*s, "air_density", *rho);
  }

  void read_material(const Section& s) {
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

  std::vector<std::string> material_names() const {
    std::vector<std::string> names;
    for (const Material& m : spec_.materials) names.push_back(m.name);
    return names;
  }

  int material_index(const Section& s, std::string_view k, const std::string& name) const {
    for (size_t i = 0; i < spec_.materials.size(); ++i)
      if (spec_.materials[i].name == name) return int(i);
    s.fail(k, "unknown material '" + name + "'" + did_you_mean(name, material_names()) +
                  " (materials: " + quoted_list(material_names()) + ")");
  }

  int material_of(const Section& s) const {
    return material_index(s, "material", s.required_text("material", " (a [[material]] name)"));
  }

  // Exactly two strings: ["a", "b"].
  std::pair<std::string, std::string> name_pair(const Section& s, std::string_view k) const {
    const toml::node* node = s.table().get(k);
    const toml::array* array = node ? node->as_array() : nullptr;
    if (!array || array->size() != 2 || !array->get(0)->is_string() || !array->get(1)->is_string())
      s.fail(k, "expected two names, as [\"a\", \"b\"]");
    return {array->get(0)->as_string()->get(), array->get(1)->as_string()->get()};
  }

  void read_interaction(const Section& s) {
    s.allow_only({"materials", "preset", "restitution", "static_friction", "rolling_friction", "spinning_friction",
                  "viscoelastic_time", "cohesion_energy_density"},
                 "an [[interaction]]");
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
    if (auto mu = s.number("spinning_friction")) in.spinning_friction = non_negative(s, "spinning_friction", *mu);
    // Extensions restitution_velocity and cohesion (docs/diagnosis.md), off unless given.
    if (auto a = s.number("viscoelastic_time")) in.viscoelastic_time = non_negative(s, "viscoelastic_time", *a);
    if (auto k = s.number("cohesion_energy_density"))
      in.cohesion_energy_density = non_negative(s, "cohesion_energy_density", *k);
    spec_.interactions.push_back(in);
  }

  // Remembers the first entry that puts a material among the particles or on a wall, so that a
  // missing [[interaction]] can be reported where the pair first meets.
  void note_use(std::map<int, SourceRef>& users, int material, const Section& s) {
    users.emplace(material, s.where("material"));
  }

  // `fixed = true`: the particles take part in contacts but never move, so they start at rest.
  bool fixed_of(const Section& s) const {
    bool fixed = s.boolean("fixed").value_or(false);
    for (const char* k : {"velocity", "angular_velocity"})
      if (fixed && s.has(k)) s.fail(k, "a fixed particle never moves: give it no velocity");
    return fixed;
  }

  void read_sphere(const Section& s) {
    s.allow_only({"material", "radius", "position", "velocity", "angular_velocity", "fixed"}, "a [[sphere]]");
    SphereSpec sphere;
    sphere.where = s.where();
    sphere.material = material_of(s);
    sphere.radius = positive(s, "radius", s.required_number("radius", " (m)"));
    sphere.position = s.required_vector3("position");
    sphere.velocity = s.vector3("velocity").value_or(Vec3d{});
    sphere.angular_velocity = s.vector3("angular_velocity").value_or(Vec3d{});
    sphere.fixed = fixed_of(s);
    note_use(particle_users_, sphere.material, s);
    spec_.spheres.push_back(sphere);
  }

  // A number, or [min, max] with 0 < min <= max.
  void positive_range(const Section& s, std::string_view k, double& low, double& high) {
    const toml::node* node = s.table().get(k);
    if (!node) return;
    if (node->is_array()) {
      const toml::array& range = *node->as_array();
      if (range.size() != 2 || !range.get(0)->is_number() || !range.get(1)->is_number())
        s.fail(k, "expected a number or [min, max]");
      low = range.get(0)->value<double>().value();
      high = range.get(1)->value<double>().value();
      if (!(low > 0)) s.fail(k, "the smallest value " + format_number(low) + " must be greater than 0");
      if (high < low) s.fail(k, "[min, max] has max < min");
    } else {
      low = high = positive(s, k, s.required_number(k));
    }
  }

  int template_of(const Section& s) const {
    std::string name = s.required_text("template", " (a [[template]] name)");
    std::vector<std::string> names;
    for (size_t t = 0; t < spec_.templates.size(); ++t) {
      if (spec_.templates[t].name == name) return int(t);
      names.push_back(spec_.templates[t].name);
    }
    if (names.empty()) s.fail("template", "no [[template]] named '" + name + "': the case defines none");
    s.fail("template", "no [[template]] named '" + name + "' (templates: " + quoted_list(names) + ")" +
                           did_you_mean(name, names));
  }

  // [[template]]: name, and builtin = "cabbage" (the shipped templates) or file = "x.csv"
  // (sphere centres and radii, relative to the case file), optional mass (kg).
  void read_template(const Section& s) {
    s.allow_only({"name", "builtin", "file", "mass"}, "a [[template]]");
    TemplateSpec t;
    t.where = s.where();
    t.name = s.required_text("name");
    for (const TemplateSpec& other : spec_.templates)
      if (other.name == t.name)
        s.fail("name", "duplicate template '" + t.name + "' (first at line " + std::to_string(other.where.line) + ")");
    if (s.has("builtin") == s.has("file"))
      s.fail(s.has("file") ? "file" : "name", "give exactly one of builtin = \"NAME\" and file = \"PATH.csv\"");
    if (auto builtin = s.text("builtin")) {
      try {
        t.clump = make_shipped_template(*builtin);
      } catch (const std::invalid_argument& error) {
        s.fail("builtin", error.what());
      }
    } else {
      std::string file = *s.text("file");
      t.file = file;
      std::filesystem::path path = std::filesystem::path(file_).parent_path() / file;
      try {
        t.clump.spheres = read_sphere_csv(path.string());
      } catch (const std::exception& error) {
        s.fail("file", error.what());
      }
      note_input_file(file, path);
    }
    t.clump.name = t.name;
    if (auto mass = s.number("mass")) t.mass = positive(s, "mass", *mass);
    spec_.templates.push_back(std::move(t));
  }

  // `orientation = [w, x, y, z]`, normalised; the identity when absent.
  std::array<double, 4> orientation_of(const Section& s) const {
    std::array<double, 4> q{1, 0, 0, 0};
    const toml::node* node = s.table().get("orientation");
    if (!node) return q;
    const toml::array* a = node->as_array();
    if (!a || a->size() != 4 || !std::all_of(a->begin(), a->end(), [](const toml::node& n) { return n.is_number(); }))
      s.fail("orientation", "expected a unit quaternion [w, x, y, z]");
    double norm = 0;
    for (size_t k = 0; k < 4; ++k) {
      q[k] = a->get(k)->value<double>().value();
      norm += q[k] * q[k];
    }
    if (!(norm > 0)) s.fail("orientation", "must not be the zero quaternion");
    for (double& c : q) c /= std::sqrt(norm);
    return q;
  }

  // [[clump]]: one body of a template at a given pose.
  void read_clump(const Section& s) {
    s.allow_only({"template", "material", "position", "orientation", "scale", "velocity", "angular_velocity", "fixed"},
                 "a [[clump]]");
    BodySpec body;
    body.where = s.where();
    body.template_index = template_of(s);
    body.material = material_of(s);
    body.position = s.required_vector3("position");
    if (auto scale = s.number("scale")) body.scale = positive(s, "scale", *scale);
    body.orientation = orientation_of(s);
    body.velocity = s.vector3("velocity").value_or(Vec3d{});
    body.angular_velocity = s.vector3("angular_velocity").value_or(Vec3d{});
    body.fixed = fixed_of(s);
    note_use(particle_users_, body.material, s);
    spec_.bodies.push_back(body);
  }

  void read_fill(const Section& s, int index) {
    s.allow_only({"material", "count", "radius", "template", "scale", "box", "cylinder", "seed", "velocity", "fixed"},
                 "a [[fill]]");
    FillSpec fill;
    fill.where = s.where();
    fill.material = material_of(s);
    auto count = s.integer("count");
    if (!count) s.missing("count", " (number of spheres or bodies)");
    if (*count <= 0 || *count > 100000000) s.fail("count", "must be between 1 and 1e8");
    fill.count = int(*count);

    // The radius that must fit in the region: a sphere's, or a body's bounding sphere.
    double reach = 0;
    if (s.has("template")) {
      if (s.has("radius")) s.fail("radius", "a template fill sizes its bodies with scale, not radius");
      fill.template_index = template_of(s);
      positive_range(s, "scale", fill.scale_min, fill.scale_max);
      reach = bounding_radius(spec_.templates[size_t(fill.template_index)].clump) * fill.scale_max;
    } else {
      if (s.has("scale")) s.fail("scale", "scale applies to template fills (give template = \"NAME\")");
      if (!s.has("radius")) s.missing("radius", " (m, or [min, max] for sizes uniform between them)");
      positive_range(s, "radius", fill.radius_min, fill.radius_max);
      reach = fill.radius_max;
    }
    double diameter = 2 * reach;

    auto box = s.sub("box");
    auto cylinder = s.sub("cylinder");
    if (box && cylinder) s.fail("cylinder", "give box or cylinder, not both");
    if (!box && !cylinder) s.missing("box", ": give box = { min = [..], max = [..] } or cylinder = { base = [..], axis = [..], radius = .., height = .. }");
    if (box) {
      box->allow_only({"min", "max"}, "a fill box");
      fill.shape = FillSpec::Shape::Box;
      fill.box_min = box->required_vector3("min");
      fill.box_max = box->required_vector3("max");
      for (int axis = 0; axis < 3; ++axis)
        if (!(fill.box_max[axis] - fill.box_min[axis] >= diameter))
          box->fail("max", "the box is " + format_number(fill.box_max[axis] - fill.box_min[axis]) +
                               " m along " + "xyz"[axis] + ", less than a sphere diameter " +
                               format_number(diameter) + " m");
    } else {
      cylinder->allow_only({"base", "axis", "radius", "height"}, "a fill cylinder");
      fill.shape = FillSpec::Shape::Cylinder;
      fill.cyl_base = cylinder->required_vector3("base");
      fill.cyl_axis = unit_vector(*cylinder, "axis", cylinder->vector3("axis").value_or(Vec3d{0, 0, 1}));
      fill.cyl_radius = cylinder->required_number("radius", " (m)");
      fill.cyl_height = cylinder->required_number("height", " (m)");
      if (!(fill.cyl_radius >= reach))
        cylinder->fail("radius", format_number(fill.cyl_radius) + " m is less than a particle radius " +
                                     format_number(reach) + " m");
      if (!(fill.cyl_height >= diameter))
        cylinder->fail("height", format_number(fill.cyl_height) + " m is less than a sphere diameter " +
                                     format_number(diameter) + " m");
    }
    if (auto seed = s.integer("seed")) {
      if (*seed < 0) s.fail("seed", "must not be negative");
      fill.seed = uint64_t(*seed);
    } else {
      fill.seed = spec_.seed + uint64_t(index);  // distinct fills draw distinct streams
    }
    fill.velocity = s.vector3("velocity").value_or(Vec3d{});
    fill.fixed = fixed_of(s);
    note_use(particle_users_, fill.material, s);
    spec_.fills.push_back(fill);
  }

  void read_lattice(const Section& s) {
    s.allow_only({"material", "type", "min", "max", "spacing", "radius", "count", "velocity", "template",
                  "orientation", "scale", "fixed"},
                 "a [[lattice]]");
    LatticeSpec lattice;
    lattice.where = s.where();
    lattice.material = material_of(s);
    lattice.fixed = fixed_of(s);
    if (s.has("template")) {
      read_body_lattice(s, lattice);
      return;
    }
    for (const char* k : {"orientation", "scale"})
      if (s.has(k)) s.fail(k, "applies to template lattices (give template = \"NAME\")");
    read_lattice_box(s, lattice);
    lattice.radius = positive(s, "radius", s.required_number("radius", " (m)"));
    lattice.spacing = positive(s, "spacing", s.required_number("spacing", " (m, the cube edge)"));
    // Nearest neighbours: the cube edge (sc) or half its diagonal (bcc) apart. The relative
    // allowance lets a spacing typed as exactly touching pass despite rounding.
    bool bcc = lattice.kind == LatticeSpec::Kind::BodyCentredCubic;
    double nearest = bcc ? lattice.spacing * std::sqrt(3.0) / 2 : lattice.spacing;
    if (nearest < 2 * lattice.radius * (1 - 1e-9))
      s.fail("spacing", format_number(lattice.spacing) + " m puts neighbours " + format_number(nearest) +
                            " m apart, closer than a diameter " + format_number(2 * lattice.radius) + " m");
    finish_lattice(s, lattice);
  }

  // type, min, max of a [[lattice]].
  void read_lattice_box(const Section& s, LatticeSpec& lattice) {
    if (!s.has("type")) s.missing("type", " ('sc' or 'bcc')");
    lattice.kind = s.choice<LatticeSpec::Kind>(
        "type", {{"sc", LatticeSpec::Kind::SimpleCubic}, {"bcc", LatticeSpec::Kind::BodyCentredCubic}},
        LatticeSpec::Kind::SimpleCubic);
    lattice.box_min = s.required_vector3("min");
    lattice.box_max = s.required_vector3("max");
    for (int axis = 0; axis < 3; ++axis)
      if (!(lattice.box_max[axis] > lattice.box_min[axis]))
        s.fail("max", std::string("max must exceed min along ") + "xyz"[axis]);
  }

  // count, velocity; then the lattice joins the case.
  void finish_lattice(const Section& s, LatticeSpec& lattice) {
    if (auto count = s.integer("count")) {
      if (*count < 0 || *count > 100000000) s.fail("count", "must be 0 (all that fit) or a positive number up to 1e8");
      lattice.max_count = int(*count);
    }
    lattice.velocity = s.vector3("velocity").value_or(Vec3d{});
    note_use(particle_users_, lattice.material, s);
    spec_.lattices.push_back(lattice);
  }

  // [[lattice]] of bodies: template, spacing (one edge or [sx, sy, sz]), orientation, scale.
  void read_body_lattice(const Section& s, LatticeSpec& lattice) {
    if (s.has("radius")) s.fail("radius", "a template lattice sizes its bodies with scale, not radius");
    lattice.template_index = template_of(s);
    read_lattice_box(s, lattice);
    const toml::node* spacing = s.table().get("spacing");
    if (!spacing) s.missing("spacing", " (m: the cell edge, or [sx, sy, sz])");
    if (spacing->is_array()) {
      lattice.spacing_xyz = s.required_vector3("spacing");
    } else {
      double edge = s.required_number("spacing");
      lattice.spacing_xyz = {edge, edge, edge};
    }
    for (int axis = 0; axis < 3; ++axis)
      if (!(lattice.spacing_xyz[axis] > 0)) s.fail("spacing", "every cell edge must be greater than 0");
    if (auto scale = s.number("scale")) lattice.scale = positive(s, "scale", *scale);
    lattice.orientation = orientation_of(s);
    finish_lattice(s, lattice);
  }

  void read_wall(const Section& s, int index) {
    if (!s.has("type")) {
      // Without a type, a misspelt "type" is likelier than a missing one: suggest among all keys.
      s.allow_only({"name", "type", "material", "motion", "point", "normal", "min", "max", "base", "axis",
                    "radius", "height", "open", "centre", "edge_axis", "size", "file", "scale", "offset"},
                   "a [[wall]]");
      s.missing("type", " ('plane', 'box', 'cylinder', 'rectangle' or 'mesh')");
    }
    WallSpec wall;
    wall.type = s.choice<WallSpec::Type>(
        "type", {{"plane", WallSpec::Type::Plane}, {"box", WallSpec::Type::Box}, {"cylinder", WallSpec::Type::Cylinder},
                 {"rectangle", WallSpec::Type::Rectangle}, {"mesh", WallSpec::Type::Mesh}},
        WallSpec::Type::Plane);
    std::vector<std::string> allowed{"name", "type", "material", "motion"};
    const char* kind = "";
    switch (wall.type) {
      case WallSpec::Type::Plane: allowed.insert(allowed.end(), {"point", "normal"}); kind = "a plane [[wall]]"; break;
      case WallSpec::Type::Box: allowed.insert(allowed.end(), {"min", "max", "open"}); kind = "a box [[wall]]"; break;
      case WallSpec::Type::Cylinder:
        allowed.insert(allowed.end(), {"base", "axis", "radius", "height"});
        kind = "a cylinder [[wall]]";
        break;
      case WallSpec::Type::Rectangle:
        allowed.insert(allowed.end(), {"centre", "normal", "edge_axis", "size"});
        kind = "a rectangle [[wall]]";
        break;
      case WallSpec::Type::Mesh: allowed.insert(allowed.end(), {"file", "scale", "offset"}); kind = "a mesh [[wall]]"; break;
    }
    s.allow_only(allowed, kind);
    wall.where = s.where();
    wall.material = material_of(s);
    if (auto name = s.text("name")) {
      if (!usable_name(*name))
        s.fail("name", "'" + *name + "' is not a usable name: letters, digits, '_' and '-', starting with a letter or '_'");
      for (const WallSpec& other : spec_.walls)
        if (other.name == *name)
          s.fail("name", "wall '" + *name + "' is already defined at line " + std::to_string(other.where.line));
      wall.name = *name;
    } else {
      wall.name = "wall[" + std::to_string(index) + "]";
    }
    switch (wall.type) {
      case WallSpec::Type::Plane:
        wall.point = s.required_vector3("point");
        wall.normal = unit_vector(s, "normal", s.required_vector3("normal"));
        break;
      case WallSpec::Type::Box:
        wall.box_min = s.required_vector3("min");
        wall.box_max = s.required_vector3("max");
        for (int axis = 0; axis < 3; ++axis)
          if (!(wall.box_max[axis] > wall.box_min[axis]))
            s.fail("max", std::string("max must exceed min along ") + "xyz"[axis]);
        wall.open_faces = box_open_faces(s);
        break;
      case WallSpec::Type::Rectangle: read_rectangle(s, wall); break;
      case WallSpec::Type::Mesh: read_mesh(s, wall); break;
      case WallSpec::Type::Cylinder:
        wall.base = s.required_vector3("base");
        wall.axis = unit_vector(s, "axis", s.vector3("axis").value_or(Vec3d{0, 0, 1}));
        wall.radius = positive(s, "radius", s.required_number("radius", " (m)"));
        wall.height = positive(s, "height", s.required_number("height", " (m)"));
        break;
    }
    if (auto motion = s.sub("motion")) read_motion(*motion, wall.motion);
    note_use(wall_users_, wall.material, s);
    spec_.walls.push_back(wall);
  }

  // `open = ["zmax"]`: faces of a box left out.
  std::vector<std::string> box_open_faces(const Section& s) {
    const toml::node* node = s.table().get("open");
    if (!node) return {};
    const std::vector<std::string> faces{"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
    const toml::array* array = node->as_array();
    if (!array) s.wrong_type("open", "an array of face names such as [\"zmax\"]");
    std::vector<std::string> open;
    for (const toml::node& element : *array) {
      if (!element.is_string()) s.fail("open", "expected face names (strings) such as \"zmax\"");
      std::string face = element.as_string()->get();
      if (std::find(faces.begin(), faces.end(), face) == faces.end())
        s.fail("open", "'" + face + "' is not one of " + quoted_list(faces) + did_you_mean(face, faces));
      open.push_back(face);
    }
    return open;
  }

  void read_rectangle(const Section& s, WallSpec& wall) {
    wall.point = s.required_vector3("centre");
    wall.normal = unit_vector(s, "normal", s.required_vector3("normal"));
    Vec3d u = unit_vector(s, "edge_axis", s.required_vector3("edge_axis"));
    double along = u[0] * wall.normal[0] + u[1] * wall.normal[1] + u[2] * wall.normal[2];
    if (std::abs(along) > 1e-6)
      s.fail("edge_axis", "must be perpendicular to the normal (their dot product is " + format_number(along) + ")");
    wall.edge_axis = u;
    const toml::node* node = s.table().get("size");
    if (!node) s.missing("size", " ([length along edge_axis, length across], m)");
    const toml::array* array = node->as_array();
    if (!array || array->size() != 2 || !array->get(0)->is_number() || !array->get(1)->is_number())
      s.fail("size", "expected [length along edge_axis, length across] in m");
    for (size_t k = 0; k < 2; ++k) {
      const toml::node& e = *array->get(k);
      wall.size[k] = e.is_integer() ? double(e.as_integer()->get()) : e.as_floating_point()->get();
      if (!(wall.size[k] > 0) || !std::isfinite(wall.size[k]))
        s.fail("size", "side lengths must be positive, got " + format_number(wall.size[k]));
    }
  }

  // The STL is read here, so that a missing, broken or empty file is reported as a case error.
  void read_mesh(const Section& s, WallSpec& wall) {
    std::string file = s.required_text("file", " (an STL file, relative to the case)");
    std::filesystem::path path(file);
    if (path.is_relative()) path = std::filesystem::path(file_).parent_path() / path;
    double scale = positive(s, "scale", s.number("scale").value_or(1.0));
    Vec3d offset = s.vector3("offset").value_or(Vec3d{0, 0, 0});
    StlFile stl;
    try {
      stl = read_stl(path.string());
    } catch (const std::exception& e) {
      s.fail("file", e.what());
    }
    note_input_file(file, path);
    auto mesh = std::make_shared<WallMesh>();
    mesh->file = path.string();
    for (const auto& v : stl.mesh.vertices)
      mesh->vertices.push_back({v.x * scale + offset[0], v.y * scale + offset[1], v.z * scale + offset[2]});
    mesh->triangles = stl.mesh.triangles;
    wall.mesh = std::move(mesh);
  }

  void read_motion(const Section& s, WallMotion& motion) {
    s.allow_only({"velocity", "start", "stop", "axis_point", "axis", "rate"}, "a wall motion");
    motion.velocity = s.vector3("velocity").value_or(motion.velocity);
    motion.start_time = non_negative(s, "start", s.number("start").value_or(motion.start_time));
    motion.stop_time = s.number("stop").value_or(motion.stop_time);
    if (!(motion.stop_time > motion.start_time))
      s.fail("stop", format_number(motion.stop_time) + " must be later than start " + format_number(motion.start_time));
    motion.rotation_axis_point = s.vector3("axis_point").value_or(motion.rotation_axis_point);
    motion.rotation_axis = unit_vector(s, "axis", s.vector3("axis").value_or(motion.rotation_axis));
    motion.angular_rate = s.number("rate").value_or(0);
  }

  // Every pair of materials that can touch (particle-particle, particle-wall) needs its
  // contact parameters: there is no sensible default for restitution or friction.
  void check_interactions_cover_use() {
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

  // How many particles of a material the case will have (before they are placed).
  size_t particles_of(int material) const {
    size_t count = 0;
    for (const SphereSpec& sphere : spec_.spheres) count += sphere.material == material;
    for (const BodySpec& body : spec_.bodies) count += body.material == material;
    for (const FillSpec& fill : spec_.fills) count += fill.material == material ? size_t(fill.count) : 0;
    for (const LatticeSpec& lattice : spec_.lattices)
      if (lattice.material == material)
        count += lattice.max_count > 0        ? size_t(lattice.max_count)
                 : lattice.template_index >= 0 ? 2  // bodies: at least a pair can meet
                                               : lattice_sites(lattice).size();
    return count;
  }

  void check_time_step() {
    RayleighLimit limit = rayleigh_limit(spec_);
    if (!spec_.time.dt || *spec_.time.dt <= limit.time) return;
    throw CaseError(spec_.time.where,
                    format_number(*spec_.time.dt) + " s is above the Rayleigh time " + format_number(limit.time) +
                        " s set by " + limit.where.key + " (line " + std::to_string(limit.where.line) +
                        ", " + (limit.body >= 0 ? "sub-sphere radius " : "radius ") +
                        format_number(limit.radius) + " m, material '" +
                        spec_.materials[size_t(limit.material)].name +
                        "'), where the contact law is unstable; lower dt or give rayleigh_fraction "
                        "(0.1 to 0.4 is usual)");
  }

  const toml::table& root_;
  const std::string& file_;
  CaseSpec spec_;
  std::map<int, SourceRef> particle_users_, wall_users_;
};

}  // namespace

CaseOverride parse_override(const std::string& text) {
  size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0)
    throw CaseError({"", "override " + text, 0}, "expected KEY=VALUE, as simulation.end_time=0.5");
  return {text.substr(0, equals), text.substr(equals + 1)};
}

CaseSpec load_case_from_string(const std::string& toml_text, const std::string& virtual_path,
                               const std::vector<CaseOverride>& overrides) {
  toml::table root;
  try {
    root = toml::parse(std::string_view(toml_text), std::string_view(virtual_path));
  } catch (const toml::parse_error& error) {
    throw CaseError({virtual_path, "", int(error.source().begin.line)},
                    "TOML syntax: " + std::string(error.description()), int(error.source().begin.column));
  }
  for (const CaseOverride& o : overrides) apply_override(root, o.key, o.value, virtual_path);
  return CaseReader(root, virtual_path).read();
}

std::string case_hash(const CaseSpec& spec) { return fnv1a_hex(spec.identity); }

CaseSpec load_case(const std::string& path, const std::vector<CaseOverride>& overrides) {
  // A case is a short TOML text; particles and meshes go in the CSV and STL files it names.
  if (auto why = why_not_input_file(path, 16u << 20); !why.empty())
    throw CaseError({path, "", 0}, "not a case file: " + why);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CaseError({path, "", 0}, std::string("cannot read the case file: ") + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  return load_case_from_string(text.str(), path, overrides);
}

}  // namespace repose
