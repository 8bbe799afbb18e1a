#include "io/vtk_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/glm.hpp>
#include <sstream>

#include "util/atomic_file.h"
#include "util/math.h"

namespace repose {

namespace {

// Raw appended data: each array is a UInt64 byte count followed by its bytes (little-endian,
// as the header declares), at the offset its DataArray element names.
class Appended {
 public:
  template <class T>
  size_t add(const std::vector<T>& values) {
    size_t offset = bytes_.size();
    uint64_t n = values.size() * sizeof(T);
    bytes_.append(reinterpret_cast<const char*>(&n), 8);
    bytes_.append(reinterpret_cast<const char*>(values.data()), n);
    return offset;
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

std::string array_element(const char* type, const char* name, int components, size_t offset) {
  std::ostringstream e;
  e << "        <DataArray type=\"" << type << "\"";
  if (name[0]) e << " Name=\"" << name << "\"";
  if (components > 1) e << " NumberOfComponents=\"" << components << "\"";
  e << " format=\"appended\" offset=\"" << offset << "\"/>\n";
  return e.str();
}

std::vector<float> xyz(const std::vector<gpu::vec4>& v) {
  std::vector<float> out;
  out.reserve(3 * v.size());
  for (const auto& a : v) out.insert(out.end(), {a.x, a.y, a.z});
  return out;
}

std::string time_field(double time) {
  char t[64];
  std::snprintf(t, sizeof t, "%.17g", time);
  return std::string("    <FieldData>\n      <DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" "
                     "format=\"ascii\">") + t + "</DataArray>\n    </FieldData>\n";
}

const char* kHeader = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" "
                      "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <PolyData>\n";

// A polygon soup: points and the polygons over them, one wall index per polygon.
struct Surface {
  std::vector<float> points;
  std::vector<int32_t> connectivity, offsets, wall_index;
  void polygon(const std::vector<glm::dvec3>& corners, int32_t wall) {
    for (const auto& c : corners) {
      connectivity.push_back(int32_t(points.size() / 3));
      points.insert(points.end(), {float(c.x), float(c.y), float(c.z)});
    }
    offsets.push_back(int32_t(connectivity.size()));
    wall_index.push_back(wall);
  }
};

glm::dvec3 d3(const gpu::vec4& v) { return {v.x, v.y, v.z}; }

// Two unit vectors spanning the plane with normal n.
void tangents(const glm::dvec3& n, glm::dvec3& u, glm::dvec3& v) {
  glm::dvec3 a = std::fabs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  u = glm::normalize(glm::cross(n, a));
  v = glm::cross(n, u);
}

// A plane as the patch that spans the drawing bounds: exact for axis-aligned planes (a box's
// faces come out as the box), a square as wide as the bounds' diagonal otherwise.
void plane_patch(Surface& s, const gpu::WallState& w, const Bounds& b, int32_t wall) {
  glm::dvec3 p = d3(w.p0), n = glm::normalize(d3(w.p1));
  glm::dvec3 lo(b.lo[0], b.lo[1], b.lo[2]), hi(b.hi[0], b.hi[1], b.hi[2]);
  for (int axis = 0; axis < 3; ++axis) {
    if (std::fabs(std::fabs(n[axis]) - 1.0) > 1e-9) continue;
    int i = (axis + 1) % 3, j = (axis + 2) % 3;
    auto corner = [&](double a, double c) {
      glm::dvec3 q = p;
      q[i] = a;
      q[j] = c;
      return q;
    };
    s.polygon({corner(lo[i], lo[j]), corner(hi[i], lo[j]), corner(hi[i], hi[j]), corner(lo[i], hi[j])}, wall);
    return;
  }
  glm::dvec3 centre = 0.5 * (lo + hi);
  centre -= n * glm::dot(centre - p, n);
  double half = 0.5 * glm::length(hi - lo);
  glm::dvec3 u, v;
  tangents(n, u, v);
  s.polygon({centre - half * u - half * v, centre + half * u - half * v, centre + half * u + half * v,
             centre - half * u + half * v}, wall);
}

void wall_polygons(Surface& s, const gpu::WallState& w, const Bounds& b, int32_t wall) {
  switch (w.info.x) {
    case gpu::kWallPlane: plane_patch(s, w, b, wall); break;
    case gpu::kWallRectangle: {
      glm::dvec3 c = d3(w.p0), u = d3(w.p2) * double(w.p2.w), v = d3(w.p3) * double(w.p3.w);
      s.polygon({c - u - v, c + u - v, c + u + v, c - u + v}, wall);
      break;
    }
    case gpu::kWallTriangle: s.polygon({d3(w.p0), d3(w.p1), d3(w.p2)}, wall); break;
    case gpu::kWallCylinder: {
      glm::dvec3 base = d3(w.p0), axis = glm::normalize(d3(w.p1)), u, v;
      double r = w.p1.w, h = w.vel.w;
      tangents(axis, u, v);
      constexpr int kSides = 48;
      for (int k = 0; k < kSides; ++k) {
        double a0 = 2 * kPi * k / kSides, a1 = 2 * kPi * (k + 1) / kSides;
        glm::dvec3 e0 = r * (std::cos(a0) * u + std::sin(a0) * v), e1 = r * (std::cos(a1) * u + std::sin(a1) * v);
        s.polygon({base + e0, base + e1, base + e1 + h * axis, base + e0 + h * axis}, wall);
      }
      break;
    }
  }
}

}  // namespace

void Bounds::add(const Vec3d& p) {
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::min(lo[k], p[k]);
    hi[k] = std::max(hi[k], p[k]);
  }
}

Bounds drawing_bounds(const Model& m) {
  Bounds b;
  for (const auto& p : m.pos) {
    b.add({p.x - p.w, p.y - p.w, p.z - p.w});
    b.add({p.x + p.w, p.y + p.w, p.z + p.w});
  }
  for (size_t w = 0; w < m.walls.size(); ++w) {
    const ModelWall& mw = m.walls[w];
    if (mw.kind == gpu::kWallPlane) {
      b.add(mw.p0);  // a box face's corner (box_min or box_max); a plane's point
      continue;
    }
    Surface s;
    wall_polygons(s, m.wall_state(w, 0.0), b, 0);
    for (size_t k = 0; k + 2 < s.points.size(); k += 3) b.add({s.points[k], s.points[k + 1], s.points[k + 2]});
  }
  return b;
}

ParticleLabels particle_labels(const Model& model) {
  ParticleLabels labels;
  labels.materials = model.material;
  for (const auto& sub : model.subs) labels.body_ids.push_back(sub.info.x);
  return labels;
}

void write_vtk_frame(const std::string& path, const HostState& s, double time, const ParticleLabels& labels) {
  size_t n = s.pos.size();
  std::vector<float> radius(n), speed(n), orientation(4 * n);
  std::vector<int32_t> id(n), body(n), material(n), offsets(n);
  for (size_t i = 0; i < n; ++i) {
    radius[i] = s.pos[i].w;
    const auto& v = s.vel[i];
    speed[i] = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    id[i] = int32_t(i);
    body[i] = labels.body_ids.empty() ? int32_t(i) : int32_t(labels.body_ids[i]);
    material[i] = labels.materials.empty() ? 0 : int32_t(labels.materials[i]);
    // The engine keeps (x, y, z, w); written (w, x, y, z) as case files give orientations.
    gpu::vec4 q = labels.body_ids.empty() || s.bodies.empty() ? gpu::vec4(0, 0, 0, 1) : s.bodies[labels.body_ids[i]].quat;
    orientation[4 * i] = q.w;
    orientation[4 * i + 1] = q.x;
    orientation[4 * i + 2] = q.y;
    orientation[4 * i + 3] = q.z;
    offsets[i] = int32_t(i + 1);
  }
  Appended data;
  std::string point_data = "      <PointData Scalars=\"radius\">\n";
  point_data += array_element("Float32", "radius", 1, data.add(radius));
  point_data += array_element("Float32", "speed", 1, data.add(speed));
  point_data += array_element("Int32", "id", 1, data.add(id));
  point_data += array_element("Int32", "body_id", 1, data.add(body));
  point_data += array_element("Int32", "material", 1, data.add(material));
  point_data += array_element("Float32", "orientation", 4, data.add(orientation));
  point_data += array_element("Float32", "velocity", 3, data.add(xyz(s.vel)));
  point_data += array_element("Float32", "angular_velocity", 3, data.add(xyz(s.omega)));
  point_data += array_element("Float32", "force", 3, data.add(xyz(s.force)));
  point_data += "      </PointData>\n";
  std::string points = "      <Points>\n" + array_element("Float32", "", 3, data.add(xyz(s.pos))) + "      </Points>\n";
  std::string verts = "      <Verts>\n" + array_element("Int32", "connectivity", 1, data.add(id)) +
                      array_element("Int32", "offsets", 1, data.add(offsets)) + "      </Verts>\n";
  write_file_atomically(path, [&](std::ostream& out) {
    out << kHeader << time_field(time) << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfVerts=\"" << n
        << "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n"
        << point_data << points << verts << "    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n   _"
        << data.bytes() << "\n  </AppendedData>\n</VTKFile>\n";
  }, true);
}

std::vector<ContactLine> touching_pairs(const HostState& s, const std::vector<gpu::vec4>& forces,
                                        const ParticleLabels& labels) {
  std::vector<ContactLine> lines;
  size_t n = s.pos.size();
  if (s.row_start.size() < n + 1) return lines;
  size_t listed = std::min<size_t>(forces.size(), s.partner.size());
  for (size_t i = 0; i < n; ++i)
    for (size_t c = s.row_start[i]; c < s.row_start[i + 1] && c < listed; ++c) {
      uint32_t j = s.partner[c];
      if (j >= n) continue;  // a wall (wall_forces.csv)
      if (!labels.body_ids.empty() && labels.body_ids[i] == labels.body_ids[j]) continue;
      const gpu::vec4 &a = s.pos[i], &b = s.pos[j];
      double dx = double(a.x) - b.x, dy = double(a.y) - b.y, dz = double(a.z) - b.z;
      double d = std::sqrt(dx * dx + dy * dy + dz * dz);
      if (!(d < double(a.w) + double(b.w)) || d == 0) continue;
      const gpu::vec4& f = forces[c];
      lines.push_back({uint32_t(i), j, float((f.x * dx + f.y * dy + f.z * dz) / d), f});
    }
  return lines;
}

void write_contact_frame(const std::string& path, const HostState& s, const std::vector<ContactLine>& lines,
                         double time) {
  std::vector<int32_t> connectivity, offsets;
  std::vector<float> normal_force, force;
  for (const ContactLine& l : lines) {
    connectivity.insert(connectivity.end(), {int32_t(l.i), int32_t(l.j)});
    offsets.push_back(int32_t(connectivity.size()));
    normal_force.push_back(l.normal_force);
    force.insert(force.end(), {l.force.x, l.force.y, l.force.z});
  }
  Appended data;
  std::string cells = "      <CellData Scalars=\"normal_force\">\n" +
                      array_element("Float32", "normal_force", 1, data.add(normal_force)) +
                      array_element("Float32", "force", 3, data.add(force)) + "      </CellData>\n";
  std::string points = "      <Points>\n" + array_element("Float32", "", 3, data.add(xyz(s.pos))) + "      </Points>\n";
  std::string line_cells = "      <Lines>\n" + array_element("Int32", "connectivity", 1, data.add(connectivity)) +
                           array_element("Int32", "offsets", 1, data.add(offsets)) + "      </Lines>\n";
  write_file_atomically(path, [&](std::ostream& out) {
    out << kHeader << time_field(time) << "    <Piece NumberOfPoints=\"" << s.pos.size()
        << "\" NumberOfVerts=\"0\" NumberOfLines=\"" << lines.size() << "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n"
        << cells << points << line_cells << "    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n   _"
        << data.bytes() << "\n  </AppendedData>\n</VTKFile>\n";
  }, true);
}

void write_wall_frame(const std::string& path, const Model& m, double time, const Bounds& bounds) {
  Surface s;
  auto group = m.wall_groups();
  for (size_t w = 0; w < m.walls.size(); ++w) wall_polygons(s, m.wall_state(w, time), bounds, int32_t(group[w]));
  Appended data;
  std::string points = "      <Points>\n" + array_element("Float32", "", 3, data.add(s.points)) + "      </Points>\n";
  std::string cells = "      <CellData Scalars=\"wall_index\">\n" +
                      array_element("Int32", "wall_index", 1, data.add(s.wall_index)) + "      </CellData>\n";
  std::string polys = "      <Polys>\n" + array_element("Int32", "connectivity", 1, data.add(s.connectivity)) +
                      array_element("Int32", "offsets", 1, data.add(s.offsets)) + "      </Polys>\n";
  write_file_atomically(path, [&](std::ostream& out) {
    out << kHeader << time_field(time) << "    <Piece NumberOfPoints=\"" << s.points.size() / 3
        << "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"" << s.offsets.size()
        << "\">\n" << cells << points << polys << "    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n   _"
        << data.bytes() << "\n  </AppendedData>\n</VTKFile>\n";
  }, true);
}

void write_pvd(const std::string& path, const std::vector<SeriesEntry>& entries) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
           "  <Collection>\n";
    char t[64];
    for (const auto& e : entries) {
      std::snprintf(t, sizeof t, "%.17g", e.time);
      out << "    <DataSet timestep=\"" << t << "\" part=\"0\" file=\"" << e.file << "\"/>\n";
    }
    out << "  </Collection>\n</VTKFile>\n";
  });
}

}  // namespace repose
