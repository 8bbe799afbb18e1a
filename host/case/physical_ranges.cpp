#include "case/physical_ranges.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "case/body_pose.h"
#include "case/case_error.h"
#include "case/time_step.h"
#include "util/number_text.h"

namespace repose {

namespace {

std::string number(double v) { return format_g(v, 4); }

void warn(std::vector<std::string>& warnings, const SourceRef& where, const std::string& what) {
  warnings.push_back(CaseError::format(where, "warning: " + what));
}

double length(const Vec3d& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// The axis-aligned box a fill region occupies.
void fill_extent(const FillSpec& f, Vec3d& lo, Vec3d& hi) {
  if (f.shape == FillSpec::Shape::Box) {
    lo = f.box_min;
    hi = f.box_max;
    return;
  }
  Vec3d top{f.cyl_base[0] + f.cyl_height * f.cyl_axis[0], f.cyl_base[1] + f.cyl_height * f.cyl_axis[1],
            f.cyl_base[2] + f.cyl_height * f.cyl_axis[2]};
  for (int k = 0; k < 3; ++k) {
    double spread = f.cyl_radius * std::sqrt(std::max(0.0, 1 - f.cyl_axis[k] * f.cyl_axis[k]));
    lo[k] = std::min(f.cyl_base[k], top[k]) - spread;
    hi[k] = std::max(f.cyl_base[k], top[k]) + spread;
  }
}

// A fill must lie on the particles' side of every plane and inside every box that overlaps it:
// particles placed behind a wall are pushed through it or fall away at the first step.
void check_fill_inside_walls(const CaseSpec& spec, const FillSpec& f, size_t index) {
  Vec3d lo, hi;
  fill_extent(f, lo, hi);
  SourceRef where = f.where;
  where.key = "fill[" + std::to_string(index) + "]." + (f.shape == FillSpec::Shape::Box ? "box" : "cylinder");
  const double margin = 1e-9;
  for (const WallSpec& w : spec.walls) {
    std::string name = w.name.empty() ? "a " + std::string(w.type == WallSpec::Type::Box ? "box" : "plane") : "'" + w.name + "'";
    if (w.type == WallSpec::Type::Plane) {
      // The region's corner farthest behind the plane.
      double lowest = 0;
      for (int k = 0; k < 3; ++k) lowest += (w.normal[k] >= 0 ? lo[k] : hi[k]) * w.normal[k];
      double offset = 0;
      for (int k = 0; k < 3; ++k) offset += w.point[k] * w.normal[k];
      double behind = (offset - lowest) / length(w.normal);
      if (behind > margin)
        throw CaseError(where, "reaches " + number(behind) + " m behind the plane " + name + " (line " +
                                   std::to_string(w.where.line) + "): the fill must lie on the side its normal points to");
    } else if (w.type == WallSpec::Type::Box) {
      bool overlaps = true;
      for (int k = 0; k < 3; ++k) overlaps &= lo[k] < w.box_max[k] && hi[k] > w.box_min[k];
      if (!overlaps) continue;  // a fill elsewhere (another box holds it)
      for (int k = 0; k < 3; ++k) {
        const char* axis = "xyz" + k;
        std::string face_lo = std::string(1, *axis) + "min", face_hi = std::string(1, *axis) + "max";
        auto open = [&](const std::string& face) {
          return std::find(w.open_faces.begin(), w.open_faces.end(), face) != w.open_faces.end();
        };
        if ((lo[k] < w.box_min[k] - margin && !open(face_lo)) || (hi[k] > w.box_max[k] + margin && !open(face_hi)))
          throw CaseError(where, "reaches outside the box " + name + " (line " + std::to_string(w.where.line) + ") along " +
                                     *axis + ": " + number(lo[k]) + " .. " + number(hi[k]) + " m against the box's " +
                                     number(w.box_min[k]) + " .. " + number(w.box_max[k]) + " m");
      }
    }
  }
}

// A particle bigger than the box that holds it is a length in the wrong unit.
void check_sizes_against_boxes(const CaseSpec& spec) {
  for (const WallSpec& w : spec.walls) {
    if (w.type != WallSpec::Type::Box) continue;
    double smallest = std::min({w.box_max[0] - w.box_min[0], w.box_max[1] - w.box_min[1], w.box_max[2] - w.box_min[2]});
    for (const SphereSpec& s : spec.spheres)
      if (2 * s.radius > smallest)
        throw CaseError(s.where, "a sphere of radius " + number(s.radius) + " m does not fit in the box '" + w.name +
                                     "' (line " + std::to_string(w.where.line) + ", " + number(smallest) +
                                     " m across): millimetres written as metres?");
  }
}

// The axis-aligned box around spheres and walls; its size is its longest edge.
struct Extent {
  Vec3d lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  void add(const Vec3d& p, double r = 0) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k] - r);
      hi[k] = std::max(hi[k], p[k] + r);
    }
  }
  bool empty() const { return lo[0] > hi[0]; }
  double size() const { return empty() ? 0 : std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}); }
};

// What a bounded wall spans (planes span nothing).
Extent wall_extent(const WallSpec& w) {
  Extent e;
  switch (w.type) {
    case WallSpec::Type::Box: e.add(w.box_min); e.add(w.box_max); break;
    case WallSpec::Type::Cylinder:
      e.add(w.base, w.radius);
      e.add({w.base[0] + w.height * w.axis[0], w.base[1] + w.height * w.axis[1], w.base[2] + w.height * w.axis[2]}, w.radius);
      break;
    case WallSpec::Type::Rectangle: e.add(w.point, 0.5 * std::max(w.size[0], w.size[1])); break;
    case WallSpec::Type::Mesh:
      if (w.mesh)
        for (const Vec3d& v : w.mesh->vertices) e.add(v);
      break;
    case WallSpec::Type::Plane: break;
  }
  return e;
}

// A mesh far larger than everything else in the case is an STL in millimetres read as metres
// (meshes are drawn in mm more often than not): a warning with the remedy.
void check_mesh_sizes(CaseSpec& spec) {
  Extent rest;
  for (const SphereSpec& s : spec.spheres) rest.add(s.position, s.radius);
  for (const BodySpec& b : spec.bodies)
    rest.add(b.position, bounding_radius(spec.templates[size_t(b.template_index)].clump) * b.scale);
  for (const WallSpec& w : spec.walls)
    if (w.type != WallSpec::Type::Mesh && !wall_extent(w).empty()) rest.add(wall_extent(w).lo), rest.add(wall_extent(w).hi);
  if (rest.empty() || !(rest.size() > 0)) return;
  for (size_t i = 0; i < spec.walls.size(); ++i) {
    const WallSpec& w = spec.walls[i];
    double size = w.type == WallSpec::Type::Mesh ? wall_extent(w).size() : 0;
    if (size > 100 * rest.size())
      warn(spec.warnings, {w.where.file, "wall[" + std::to_string(i) + "].file", w.where.line},
           "the mesh is " + number(size) + " m across, " + number(size / rest.size()) + " times the " + number(rest.size()) +
               " m the particles and other walls span: an STL in millimetres? give scale = 0.001");
  }
}

// A template's bodies far larger than the rig, or than any granule, are a sphere CSV written in
// millimetres: blamed on the file, before the time step (which follows the radii) says more.
void check_template_sizes(const CaseSpec& spec) {
  Extent largest;
  std::string largest_name;
  for (const WallSpec& w : spec.walls)
    if (wall_extent(w).size() > largest.size()) largest = wall_extent(w), largest_name = w.name;
  for (size_t t = 0; t < spec.templates.size(); ++t) {
    const TemplateSpec& templ = spec.templates[t];
    double scale = 0, radius = 0;
    for (const BodySpec& b : spec.bodies)
      if (b.template_index == int(t)) scale = std::max(scale, b.scale);
    for (const auto& sphere : templ.clump.spheres) radius = std::max(radius, sphere.radius);
    double across = 2 * bounding_radius(templ.clump) * scale;
    bool beyond_rig = largest.size() > 0 && across > 10 * largest.size();
    if (templ.file.empty() || !(across > 20 || beyond_rig)) continue;
    throw CaseError({templ.where.file, "template[" + std::to_string(t) + "].file", templ.where.line},
                    templ.file + ": its bodies are " + number(across) + " m across (radii up to " + number(radius * scale) +
                        " m in column 'radius'), " +
                        (beyond_rig ? "more than ten times the largest wall, '" + largest_name + "' (" + number(largest.size()) + " m)"
                                    : "larger than any granule") + ": millimetres written as metres?");
  }
}

// dt against end_time, and each particle's initial travel per step against its radius.
void check_time_scales(CaseSpec& spec) {
  double dt = resolve_dt(spec);
  if (dt >= spec.time.end_time)
    throw CaseError(spec.time.where, "the time step " + number(dt) + " s is not shorter than end_time " +
                                         number(spec.time.end_time) + " s (a modulus in MPa written as Pa? the step "
                                         "follows the Rayleigh time, which grows as the modulus falls)");
  if (spec.time.end_time / dt > 1e12)
    throw CaseError(spec.time.end_where, "end_time " + number(spec.time.end_time) + " s is " +
                                         number(spec.time.end_time / dt) + " steps of " + number(dt) +
                                         " s: more than 1e12 steps cannot be meant");
  if (spec.time.end_time / dt > 1e9)
    warn(spec.warnings, spec.time.where, "a time step of " + number(dt) + " s makes " + number(spec.time.end_time / dt) +
                                             " steps to end_time " + number(spec.time.end_time) +
                                             " s: days of computing at any speed (1e12 steps are refused)");
  if (spec.time.end_time / dt < 20)
    warn(spec.warnings, spec.time.where, "only " + number(spec.time.end_time / dt) + " steps of " + number(dt) +
                                             " s before end_time " + number(spec.time.end_time) + " s");
  auto check_speed = [&](const Vec3d& v, double radius, const SourceRef& where) {
    double travel = length(v) * dt;
    if (travel > radius)
      throw CaseError(where, "a speed of " + number(length(v)) + " m/s moves " + number(travel) + " m per step of " +
                                 number(dt) + " s, more than the particle's radius " + number(radius) +
                                 " m: it would pass through walls and particles unseen");
    if (travel > 0.2 * radius)
      warn(spec.warnings, where, "a speed of " + number(length(v)) + " m/s moves " + number(travel / radius) +
                                     " radii per step: contacts at that speed are resolved coarsely");
  };
  for (const SphereSpec& s : spec.spheres) check_speed(s.velocity, s.radius, s.where);
  for (const BodySpec& b : spec.bodies) {
    double smallest = 1e300;
    for (const auto& sphere : spec.templates[size_t(b.template_index)].clump.spheres)
      smallest = std::min(smallest, sphere.radius * b.scale);
    check_speed(b.velocity, smallest, b.where);
  }
}

}  // namespace

void check_density(double density, const SourceRef& where, std::vector<std::string>& warnings) {
  if (density < 1)
    throw CaseError(where, number(density) + " kg/m^3 is lighter than air: g/cm^3 written as kg/m^3? (" +
                               number(density) + " g/cm^3 = " + number(density * 1000) + " kg/m^3)");
  if (density > 25000)
    throw CaseError(where, number(density) + " kg/m^3 is denser than any solid (osmium: 22,590)");
  if (density < 10) warn(warnings, where, number(density) + " kg/m^3 is lighter than any foam granule");
}

void check_shear_modulus(double g, const SourceRef& where, std::vector<std::string>& warnings) {
  if (g < 100)
    throw CaseError(where, number(g) + " Pa is softer than any solid: MPa written as Pa? (" + number(g) + " MPa = " +
                               number(g * 1e6) + " Pa)");
  if (g > 1e12) throw CaseError(where, number(g) + " Pa is stiffer than diamond (about 5e11 Pa)");
  if (g < 1e4) warn(warnings, where, number(g) + " Pa is softer than the softest foam granules (about 1e4 Pa)");
}

void check_case_ranges(CaseSpec& spec) {
  check_sizes_against_boxes(spec);
  check_template_sizes(spec);
  check_mesh_sizes(spec);
  for (size_t f = 0; f < spec.fills.size(); ++f) check_fill_inside_walls(spec, spec.fills[f], f);
  check_time_scales(spec);
}

}  // namespace repose
