// Mesh walls in case files: the STL is read with the case, scaled and offset, and a missing,
// empty or broken file is a case error naming the case file, the key and the STL's problem.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "case/case_error.h"
#include "case/case_loader.h"
#include "engine/model.h"

using namespace repose;
namespace fs = std::filesystem;

namespace {

fs::path scratch() {
  fs::path dir = fs::temp_directory_path() / "repose_test_walls_stl";
  fs::create_directories(dir);
  return dir;
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

std::string mesh_case(const std::string& file, const std::string& extra = "") {
  return "[simulation]\nend_time = 0.1\nrayleigh_fraction = 0.2\n"
         "[[material]]\nname = \"g\"\ndensity = 1000\nshear_modulus = 1e6\npoisson = 0.3\n"
         "[[material]]\nname = \"s\"\ndensity = 7800\nshear_modulus = 8e10\npoisson = 0.3\n"
         "[[interaction]]\nmaterials = [\"g\", \"s\"]\nrestitution = 0.5\nstatic_friction = 0.5\nrolling_friction = 0.0\n"
         "[[sphere]]\nmaterial = \"g\"\nradius = 0.01\nposition = [0, 0, 0.5]\n"
         "[[wall]]\nname = \"plate\"\ntype = \"mesh\"\nmaterial = \"s\"\nfile = \"" + file + "\"\n" + extra;
}

const char* kPlate =
    "solid plate\n"
    "facet normal 0 0 1\n outer loop\n  vertex -1 -1 0\n  vertex 1 -1 0\n  vertex 1 1 0\n endloop\nendfacet\n"
    "facet normal 0 0 1\n outer loop\n  vertex -1 -1 0\n  vertex 1 1 0\n  vertex -1 1 0\n endloop\nendfacet\n"
    "endsolid plate\n";

std::string error_of(const std::string& case_text, const fs::path& case_path) {
  write(case_path, case_text);
  try {
    load_case(case_path.string());
  } catch (const CaseError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("mesh wall from an STL: scaled, offset, one wall row per triangle with shared vertex ids", "[walls]") {
  fs::path dir = scratch();
  write(dir / "plate.stl", kPlate);
  write(dir / "mesh_ok.toml", mesh_case("plate.stl", "scale = 0.1\noffset = [0, 0, 0.2]\n"));
  CaseSpec spec = load_case((dir / "mesh_ok.toml").string());
  Model model = build_model(spec);
  REQUIRE(model.walls.size() == 2);
  CHECK(model.walls[0].kind == gpu::kWallTriangle);
  CHECK(model.walls[0].p1[0] == Approx(0.1));
  CHECK(model.walls[0].p1[2] == Approx(0.2));
  CHECK(model.walls[0].p3[2] == Approx(1.0));
  CHECK(model.walls[0].vertex_ids[0] == model.walls[1].vertex_ids[0]);  // the shared corner
  CHECK(model.wall_group_names() == std::vector<std::string>{"plate"});
}

TEST_CASE("a missing, empty or broken STL is a case error naming the case, the key and the problem", "[walls]") {
  fs::path dir = scratch();
  write(dir / "empty.stl", "");
  write(dir / "broken.stl", "solid x\nfacet normal 0 0 1\n outer loop\n  vertex 0 0\n");
  write(dir / "no_triangles.stl", "solid x\nendsolid x\n");
  struct Bad { const char* file; const char* says; };
  for (Bad bad : {Bad{"missing.stl", "missing.stl"}, Bad{"empty.stl", "empty"}, Bad{"broken.stl", "broken.stl:5:1: expected a number"},
                  Bad{"no_triangles.stl", "no triangles"}}) {
    std::string message = error_of(mesh_case(bad.file), dir / "mesh_bad.toml");
    INFO(bad.file << ": " << message);
    CHECK(message.find("mesh_bad.toml:") != std::string::npos);
    CHECK(message.find("file") != std::string::npos);
    CHECK(message.find(bad.says) != std::string::npos);
  }
}

TEST_CASE("rectangle keys are checked: edge_axis in the plane, positive sizes", "[walls]") {
  fs::path dir = scratch();
  std::string rect =
      "[[wall]]\nname = \"r\"\ntype = \"rectangle\"\nmaterial = \"s\"\ncentre = [0, 0, 0]\nnormal = [0, 0, 1]\n";
  std::string base = mesh_case("x.stl");
  base = base.substr(0, base.find("[[wall]]"));
  std::string m1 = error_of(base + rect + "edge_axis = [0, 1, 1]\nsize = [1, 1]\n", dir / "rect_bad.toml");
  CHECK(m1.find("edge_axis") != std::string::npos);
  CHECK(m1.find("perpendicular") != std::string::npos);
  std::string m2 = error_of(base + rect + "edge_axis = [1, 0, 0]\nsize = [1, -2]\n", dir / "rect_bad.toml");
  CHECK(m2.find("size") != std::string::npos);
  CHECK(m2.find("rect_bad.toml:") != std::string::npos);
}
