#include "geometry/stl_shapes.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "util/math.h"

namespace repose {

TriangleMesh hopper_mesh(double top_radius, double outlet_radius, double height, int sides) {
  if (!(top_radius > 0 && outlet_radius > 0 && height > 0) || sides < 3)
    throw std::invalid_argument("a hopper needs positive radii and height and at least 3 sides");
  TriangleMesh m;
  for (int k = 0; k < sides; ++k) {
    double a = 2 * kPi * k / sides;
    m.vertices.push_back({outlet_radius * std::cos(a), outlet_radius * std::sin(a), 0.0});
    m.vertices.push_back({top_radius * std::cos(a), top_radius * std::sin(a), height});
  }
  auto lower = [&](int k) { return uint32_t(2 * (k % sides)); };
  for (int k = 0; k < sides; ++k) {
    // Wound so that the normals point into the hopper (towards the axis), the side grains touch.
    m.triangles.push_back({lower(k), lower(k) + 1, lower(k + 1)});
    m.triangles.push_back({lower(k + 1), lower(k) + 1, lower(k + 1) + 1});
  }
  for (const auto& t : m.triangles) {
    glm::dvec3 n = glm::cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]]);
    m.normals.push_back(n / glm::length(n));
  }
  return m;
}

void write_ascii_stl(std::ostream& out, const TriangleMesh& mesh, const std::string& name) {
  char line[256];
  out << "solid " << name << "\n";
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::dvec3& n = mesh.normals[t];
    std::snprintf(line, sizeof line, "  facet normal %.9g %.9g %.9g\n    outer loop\n", n.x, n.y, n.z);
    out << line;
    for (uint32_t v : mesh.triangles[t]) {
      const glm::dvec3& p = mesh.vertices[v];
      std::snprintf(line, sizeof line, "      vertex %.9g %.9g %.9g\n", p.x, p.y, p.z);
      out << line;
    }
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid " << name << "\n";
}

}  // namespace repose
