// STL reading: ASCII and binary cubes, and clear errors for broken or empty files. The files are
// written by the tests into a temporary directory.
#include <catch2/catch.hpp>

#include <array>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "util/input_error.h"
#include "geometry/stl.h"

using namespace repose;

namespace {

using Triangle = std::array<glm::dvec3, 3>;

// Unit cube [0,1]^3, outward winding, 12 triangles.
std::vector<Triangle> cube() {
  const glm::dvec3 v[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int faces[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                            {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  std::vector<Triangle> out;
  for (const auto& f : faces) out.push_back({v[f[0]], v[f[1]], v[f[2]]});
  return out;
}

std::string ascii_stl(const std::vector<Triangle>& triangles) {
  std::ostringstream s;
  s << "solid cube\n";
  for (const auto& t : triangles) {
    s << "  facet normal 0 0 0\n    outer loop\n";
    for (const auto& v : t) s << "      vertex " << v.x << " " << v.y << " " << v.z << "\n";
    s << "    endloop\n  endfacet\n";
  }
  s << "endsolid cube\n";
  return s.str();
}

std::string binary_stl(const std::vector<Triangle>& triangles, uint32_t count_override = UINT32_MAX) {
  std::string bytes(80, ' ');
  std::memcpy(bytes.data(), "binary cube", 11);
  uint32_t count = count_override == UINT32_MAX ? static_cast<uint32_t>(triangles.size()) : count_override;
  bytes.append(reinterpret_cast<const char*>(&count), 4);  // little-endian host
  for (const auto& t : triangles) {
    float record[12] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) record[3 + 3 * k + c] = static_cast<float>(t[k][c]);
    bytes.append(reinterpret_cast<const char*>(record), sizeof record);
    bytes.append(2, '\0');
  }
  return bytes;
}

std::string write_temp(const std::string& name, const std::string& bytes) {
  const auto path = std::filesystem::temp_directory_path() / ("repose_test_" + name);
  std::ofstream(path, std::ios::binary) << bytes;
  return path.string();
}

std::string error_of(const std::string& bytes) {
  try {
    parse_stl(bytes, "wall.stl");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

void check_unit_cube(const StlFile& f) {
  CHECK(f.triangles_in_file == 12);
  CHECK(f.mesh.triangles.size() == 12);
  CHECK(f.mesh.vertices.size() == 8);  // deduplicated from 36 corners
  CHECK(f.degenerate.empty());
  const MeshSummary s = summarize_mesh(f.mesh);
  CHECK(s.area == Approx(6.0).epsilon(1e-12));
  CHECK(s.volume == Approx(1.0).epsilon(1e-12));
  CHECK(s.watertight);
  CHECK(s.lower == glm::dvec3(0, 0, 0));
  CHECK(s.upper == glm::dvec3(1, 1, 1));
  // Normals come from the winding: the first two triangles are the bottom face, facing -z.
  CHECK(f.mesh.normals[0] == glm::dvec3(0, 0, -1));
}

}  // namespace

TEST_CASE("ASCII STL cube: deduplicated, watertight, area 6, volume 1", "[stl]") {
  const StlFile f = read_stl(write_temp("cube_ascii.stl", ascii_stl(cube())));
  CHECK_FALSE(f.binary);
  CHECK(f.solid_name == "cube");
  check_unit_cube(f);
}

TEST_CASE("binary STL cube: same mesh as ASCII", "[stl]") {
  const StlFile f = read_stl(write_temp("cube_binary.stl", binary_stl(cube())));
  CHECK(f.binary);
  CHECK(f.solid_name == "binary cube");
  check_unit_cube(f);
  // A binary file whose header starts with "solid" (some exporters do this) is still binary.
  std::string tricky = binary_stl(cube());
  std::memcpy(tricky.data(), "solid cube", 10);
  CHECK(parse_stl(tricky, "tricky.stl").binary);
}

TEST_CASE("an open or misoriented mesh is not watertight", "[stl]") {
  auto open = cube();
  open.pop_back();
  MeshSummary s = summarize_mesh(parse_stl(ascii_stl(open), "open.stl").mesh);
  CHECK_FALSE(s.watertight);
  CHECK(s.boundary_edges == 3);
  auto flipped = cube();
  std::swap(flipped[0][1], flipped[0][2]);
  s = summarize_mesh(parse_stl(ascii_stl(flipped), "flipped.stl").mesh);
  CHECK_FALSE(s.watertight);
  CHECK(s.misoriented_edges == 3);
}

TEST_CASE("broken and empty STL files give clear errors", "[stl]") {
  CHECK(error_of("") == "wall.stl: file is empty");
  CHECK(error_of(std::string(40, '\x01')) ==
        "wall.stl: truncated binary STL: 40 bytes, fewer than the 84 of the header and triangle count");
  std::string truncated = binary_stl(cube());
  truncated.resize(truncated.size() - 30);
  CHECK(error_of(truncated) ==
        "wall.stl: binary STL size mismatch: the header announces 12 triangles (684 bytes) but the file "
        "has 654 bytes (truncated)");
  CHECK(error_of(binary_stl(cube(), 11)) ==
        "wall.stl: binary STL size mismatch: the header announces 11 triangles (634 bytes) but the file "
        "has 684 bytes (bad triangle count or trailing data)");
  CHECK(error_of(binary_stl({})) == "wall.stl: STL contains no triangles");
  CHECK(error_of("solid empty\nendsolid empty\n") == "wall.stl: STL contains no triangles");

  std::string typo = ascii_stl(cube());
  typo.replace(typo.find("vertex", 200), 6, "vertx");
  CHECK_THAT(error_of(typo), Catch::Matches("wall\\.stl:[0-9]+:7: expected 'vertex', found 'vertx'"));
  CHECK(error_of("solid a\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 zero\n") ==
        "wall.stl:5:15: expected a number (vertex z), found 'zero'");
  CHECK(error_of("solid a\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n") ==
        "wall.stl:5:1: expected 'vertex', found end of file");
  std::string no_end = ascii_stl(cube());
  no_end.resize(no_end.find("endsolid"));
  CHECK_THAT(error_of(no_end), Catch::Matches("wall\\.stl:[0-9]+:1: expected 'facet' or 'endsolid', found end of "
                                              "file \\(file truncated\\?\\)"));
  CHECK_THROWS_WITH(read_stl("/nonexistent/wall.stl"), "/nonexistent/wall.stl: cannot open file");
}

TEST_CASE("degenerate triangles are dropped and reported", "[stl]") {
  auto triangles = cube();
  triangles.push_back({glm::dvec3(0, 0, 0), glm::dvec3(0, 0, 0), glm::dvec3(1, 1, 1)});  // repeated corner
  triangles.push_back({glm::dvec3(0, 0, 0), glm::dvec3(0.5, 0.5, 0.5), glm::dvec3(1, 1, 1)});  // collinear
  const StlFile f = parse_stl(ascii_stl(triangles), "wall.stl");
  CHECK(f.triangles_in_file == 14);
  CHECK(f.mesh.triangles.size() == 12);
  REQUIRE(f.degenerate.size() == 2);
  CHECK(f.degenerate[0].index == 13);
  CHECK(f.degenerate[0].line == 2 + 12 * 7);
  CHECK(f.degenerate[0].reason == "two corners are the same point");
  CHECK(f.degenerate[1].reason == "corners are collinear (zero area)");
  CHECK(summarize_mesh(f.mesh).watertight);

  const std::vector<Triangle> only_bad = {{glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(2, 0, 0)}};
  CHECK(error_of(binary_stl(only_bad)) ==
        "wall.stl: all 1 triangles are degenerate (zero area); first: triangle 1: corners are collinear (zero area)");
}

TEST_CASE("ASCII STL keywords are read without regard to case", "[stl]") {
  std::string upper = ascii_stl(cube());
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  const StlFile f = parse_stl(upper, "upper.stl");
  CHECK_FALSE(f.binary);
  check_unit_cube(f);
}
