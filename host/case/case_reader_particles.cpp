// A case file's particles: its [[sphere]], [[template]], [[clump]], [[fill]] and [[lattice]]
// entries.
#include "case/case_reader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "case/body_pose.h"
#include "case/case_error.h"
#include "case/particle_factory.h"
#include "case/spelling.h"
#include "geometry/sphere_csv.h"
#include "geometry/templates.h"

namespace repose {

// `fixed = true`: the particles take part in contacts but never move, so they start at rest.
bool CaseReader::fixed_of(const Section& s) const {
  bool fixed = s.boolean("fixed").value_or(false);
  for (const char* k : {"velocity", "angular_velocity"})
    if (fixed && s.has(k)) s.fail(k, "a fixed particle never moves: give it no velocity");
  return fixed;
}

void CaseReader::read_sphere(const Section& s) {
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
void CaseReader::positive_range(const Section& s, std::string_view k, double& low, double& high) {
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

int CaseReader::template_of(const Section& s) const {
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
void CaseReader::read_template(const Section& s) {
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
std::array<double, 4> CaseReader::orientation_of(const Section& s) const {
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
void CaseReader::read_clump(const Section& s) {
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

void CaseReader::read_fill(const Section& s, int index) {
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

void CaseReader::read_lattice(const Section& s) {
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
void CaseReader::read_lattice_box(const Section& s, LatticeSpec& lattice) {
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
void CaseReader::finish_lattice(const Section& s, LatticeSpec& lattice) {
  if (auto count = s.integer("count")) {
    if (*count < 0 || *count > 100000000) s.fail("count", "must be 0 (all that fit) or a positive number up to 1e8");
    lattice.max_count = int(*count);
  }
  lattice.velocity = s.vector3("velocity").value_or(Vec3d{});
  note_use(particle_users_, lattice.material, s);
  spec_.lattices.push_back(lattice);
}

// [[lattice]] of bodies: template, spacing (one edge or [sx, sy, sz]), orientation, scale.
void CaseReader::read_body_lattice(const Section& s, LatticeSpec& lattice) {
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

// How many particles of a material the case will have (before they are placed).
size_t CaseReader::particles_of(int material) const {
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

}  // namespace repose
