// Sphere CSV files: round trip, and errors that name file, line and column.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "util/input_error.h"
#include "geometry/sphere_csv.h"

using namespace repose;

namespace {

std::vector<Sphere> parse(const std::string& text) {
  std::istringstream in(text);
  return parse_sphere_csv(in, "heap.csv");
}

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("sphere CSV round-trips bit for bit", "[csv]") {
  std::vector<Sphere> spheres = {{{0.1, -2e-3, 1.0 / 3.0}, 0.001}, {{1e-17, 5.5, -0.25}, 0.08}};
  const auto path = std::filesystem::temp_directory_path() / "repose_test_roundtrip.csv";
  write_sphere_csv(path.string(), spheres);
  const std::vector<Sphere> back = read_sphere_csv(path.string());
  REQUIRE(back.size() == spheres.size());
  for (size_t i = 0; i < back.size(); ++i) {
    CHECK(back[i].centre == spheres[i].centre);
    CHECK(back[i].radius == spheres[i].radius);
  }
  std::filesystem::remove(path);
}

TEST_CASE("sphere CSV finds columns by header name and skips comments", "[csv]") {
  auto s = parse("# settled heap\nid, radius ,Z,y,x,vx\r\n7,0.5,3,2,1,0\n\n8,0.25,6,5,4,0\n");
  REQUIRE(s.size() == 2);
  CHECK(s[0].centre == glm::dvec3(1, 2, 3));
  CHECK(s[0].radius == 0.5);
  CHECK(s[1].centre == glm::dvec3(4, 5, 6));
  CHECK(parse("x,y,z,r\n1,2,3,+4e-3\n")[0].radius == 4e-3);
}

TEST_CASE("sphere CSV errors name file, line and column", "[csv]") {
  CHECK(error_of("") == "heap.csv: file is empty");
  CHECK(error_of("x,y,z,radius\n") == "heap.csv:1: no spheres after the header");
  CHECK(error_of("# only a comment\n") == "heap.csv: no header line (only comments or blank lines)");
  CHECK(error_of("1,2,3,4\n") == "heap.csv:1:1: missing header line: expected column names such as x,y,z,radius");
  CHECK(error_of("x,y,radius\n") == "heap.csv:1:1: header lacks column 'z' (expected x,y,z,radius)");
  CHECK(error_of("x,y,z,radius\n0,0,0,1\n0,0,abc,1\n") ==
        "heap.csv:3:5: field 3 ('z'): 'abc' is not a number");
  CHECK(error_of("x,y,z,radius\n0,0,0,-0.5\n") == "heap.csv:2:7: radius -0.5 is negative (radii must be positive)");
  CHECK(error_of("x,y,z,radius\n0,0,0,0\n") == "heap.csv:2:7: radius 0 is zero (radii must be positive)");
  CHECK(error_of("x,y,z,radius\n0,0,0\n") == "heap.csv:2:6: expected 4 fields as in the header, found 3");
  CHECK(error_of("x,y,z,radius\n0,0,0,1,9\n") == "heap.csv:2:9: expected 4 fields as in the header, found 5");
  CHECK(error_of("x,y,z,radius\n0,nan,0,1\n") == "heap.csv:2:3: field 2 ('y'): 'nan' is not finite");
  CHECK(error_of("x,y,z,radius\n0,,0,1\n") == "heap.csv:2:3: field 2 ('y'): '' is not a number");
  CHECK(error_of("x,x,y,z,radius\n") == "heap.csv:1:3: header names column 'x' twice");
}

TEST_CASE("a missing sphere CSV is a clear error", "[csv]") {
  CHECK_THROWS_WITH(read_sphere_csv("/nonexistent/heap.csv"), "/nonexistent/heap.csv: cannot open file");
}
