// Meshes Repose writes itself (`repose mesh`): the hopper is the frustum it is asked for, its
// facets face the grains inside, it reads back as written, and the shipped hopper.stl is what its
// documented command writes (byte for byte).
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <glm/geometric.hpp>
#include <sstream>

#include "geometry/stl.h"
#include "geometry/stl_shapes.h"

using namespace repose;

TEST_CASE("a hopper mesh is the frustum asked for, facing its axis", "[geometry][stl]") {
  TriangleMesh m = hopper_mesh(150, 40, 300, 48);
  REQUIRE(m.triangles.size() == 96);
  MeshSummary s = summarize_mesh(m);
  CHECK(s.upper.z == Approx(300));
  CHECK(s.lower.z == Approx(0));
  CHECK(s.upper.x == Approx(150));
  CHECK(s.boundary_edges == 96);  // open at the top and at the outlet: 48 edges each
  CHECK(s.misoriented_edges == 0);
  // A 48-gon frustum's lateral area: 48 trapezoids, each (a + b) / 2 x slant height.
  double a = 2 * 150 * std::sin(M_PI / 48), b = 2 * 40 * std::sin(M_PI / 48);
  double apothem_step = (150 - 40) * std::cos(M_PI / 48), slant = std::hypot(apothem_step, 300.0);
  CHECK(s.area == Approx(48 * 0.5 * (a + b) * slant).epsilon(1e-12));
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    glm::dvec3 c = (m.vertices[m.triangles[t][0]] + m.vertices[m.triangles[t][1]] + m.vertices[m.triangles[t][2]]) / 3.0;
    CHECK(glm::dot(m.normals[t], glm::dvec3(c.x, c.y, 0)) < 0);  // towards the axis
  }
}

TEST_CASE("the shipped hopper.stl is what `repose mesh hopper` writes, and reads back", "[geometry][stl]") {
  std::ostringstream written;
  write_ascii_stl(written, hopper_mesh(150, 40, 300, 48), "hopper");
  const std::string path = std::string(REPOSE_SOURCE_DIR) + "/cases/experiments/hopper.stl";
  std::ifstream in(path, std::ios::binary);
  std::string shipped((std::istreambuf_iterator<char>(in)), {});
  CHECK(shipped == written.str());
  StlFile f = read_stl(path);
  CHECK(f.mesh.triangles.size() == 96);
  CHECK(f.degenerate.empty());
  CHECK(f.solid_name == "hopper");
}
