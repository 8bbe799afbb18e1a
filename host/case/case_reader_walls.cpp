// A case file's [[wall]] entries (planes, boxes, cylinders, rectangles, meshes) with their motion,
// and the check of the walls [experiment] names.
#include "case/case_reader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "case/case_error.h"
#include "case/spelling.h"
#include "geometry/stl.h"

namespace repose {

void CaseReader::read_wall(const Section& s, int index) {
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
std::vector<std::string> CaseReader::box_open_faces(const Section& s) {
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

void CaseReader::read_rectangle(const Section& s, WallSpec& wall) {
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
void CaseReader::read_mesh(const Section& s, WallSpec& wall) {
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

void CaseReader::read_motion(const Section& s, WallMotion& motion) {
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

// The walls [experiment] names must exist (checked once all walls are read).
void CaseReader::check_experiment_walls() {
  std::vector<std::string> names;
  for (const WallSpec& w : spec_.walls) names.push_back(w.name);
  for (const auto& [name, where] : named_walls_)
    if (!name.empty() && std::find(names.begin(), names.end(), name) == names.end())
      throw CaseError(where, "no [[wall]] is named '" + name + "'" + did_you_mean(name, names));
}

}  // namespace repose
