// STL meshes (ASCII and binary) for triangle-mesh walls.
//
// The reader deduplicates vertices by exact coordinate equality (STL stores each triangle's
// corners separately), recomputes unit face normals from the winding (stored normals are often
// zero or stale, so they are ignored), and drops degenerate triangles (a repeated vertex or zero
// area) while reporting each one by its position in the file. Every problem that prevents a
// usable mesh throws InputError naming the file, and the line and column for ASCII files.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace repose {

struct TriangleMesh {
  std::vector<glm::dvec3> vertices;               // metres as in the file (STL has no units)
  std::vector<std::array<uint32_t, 3>> triangles;  // indices into vertices, file winding
  std::vector<glm::dvec3> normals;                 // unit face normals, right-hand rule
};

struct DegenerateTriangle {
  size_t index = 0;  // 1-based position among the file's triangles
  int line = 0;      // ASCII: line of its "facet"; binary: 0
  std::string reason;
};

struct StlFile {
  TriangleMesh mesh;
  bool binary = false;
  std::string solid_name;                    // ASCII "solid NAME"; binary: the 80-byte header, trimmed
  size_t triangles_in_file = 0;              // before dropping degenerate ones
  std::vector<DegenerateTriangle> degenerate;  // dropped, in file order
};

// Reads an STL file. Binary is recognised by its size (84 + 50 * count bytes), ASCII by its
// leading "solid" and text content. Throws InputError for: a missing or empty file, a binary file
// whose size does not match its triangle count (truncated or bad count), an ASCII syntax error
// (line and column, expected vs found), a non-finite coordinate, no triangles at all, and all
// triangles degenerate.
StlFile read_stl(const std::string& path);

// The same from the file's bytes; source_name is used in error messages.
StlFile parse_stl(const std::string& bytes, const std::string& source_name);

struct MeshSummary {
  size_t triangle_count = 0;
  size_t vertex_count = 0;
  glm::dvec3 lower{0.0}, upper{0.0};  // axis-aligned bounds
  double area = 0.0;                 // m^2
  // Closed: every edge is shared by exactly two triangles that traverse it in opposite
  // directions (a consistently oriented, watertight 2-manifold).
  bool watertight = false;
  size_t boundary_edges = 0;       // edges used by one triangle
  size_t non_manifold_edges = 0;   // edges used by three or more
  size_t misoriented_edges = 0;    // edges used twice in the same direction
  double volume = 0.0;             // signed enclosed volume (divergence theorem); meaningful when watertight
};
MeshSummary summarize_mesh(const TriangleMesh& mesh);

}  // namespace repose
