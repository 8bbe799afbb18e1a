// The geometry verbs as a user runs them: `repose template`, `repose clump`, `repose stl`.
#include <catch2/catch.hpp>

#include "tests/cli_support.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <sys/wait.h>

namespace {

using Run = repose::test::CliRun;
Run run(const std::string& arguments) { return repose::test::run_repose(arguments); }

std::string temp(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("repose_verbs_" + name)).string();
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("repose template writes the shipped CSV", "[verbs]") {
  const std::string out = temp("stalk.csv");
  const Run r = run("template cotton_stalk --out " + out);
  CHECK(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("720 sub-spheres"));
  CHECK(slurp(out) == slurp(std::string(REPOSE_SOURCE_DIR) + "/cases/templates/cotton_stalk.csv"));
  const Run bad = run("template lettuce --out " + out);
  CHECK(bad.status != 0);
  CHECK_THAT(bad.output, Catch::Contains("unknown template 'lettuce'"));
}

TEST_CASE("repose clump prints mass properties, as text or JSON", "[verbs]") {
  const std::string csv = std::string(REPOSE_SOURCE_DIR) + "/cases/templates/cotton_stalk_coarse.csv";
  Run r = run("clump " + csv + " --density 120");
  CHECK(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("48 sub-spheres"));
  CHECK_THAT(r.output, Catch::Contains("principal moments"));
  r = run("clump " + csv + " --density 120 --json");
  CHECK(r.status == 0);
  const nlohmann::ordered_json j = nlohmann::ordered_json::parse(r.output);  // the whole output is one JSON document
  CHECK(j.begin().key() == "file");
  CHECK(j["sub_spheres"] == 48);
  REQUIRE(j["principal_axes"].size() == 3);
  CHECK(j["principal_axes"][0].size() == 3);

  const std::string principal = temp("principal.csv");
  r = run("clump " + csv + " --principal-out " + principal);
  CHECK(r.status == 0);
  CHECK(std::filesystem::file_size(principal) > 100);

  r = run("clump " + csv + " --mass 0.001 --com 0,0,0 --inertia 1e-7,1e-7,3e-9,0,0,0");
  CHECK(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("given explicitly"));
  r = run("clump " + csv + " --mass 0.001");
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Catch::Contains("need all of --mass"));
}

TEST_CASE("repose clump names the file, line and column of a bad CSV", "[verbs]") {
  const std::string bad = temp("bad.csv");
  std::ofstream(bad) << "x,y,z,radius\n0,0,0,0.01\n0,0,0,-0.01\n";
  const Run r = run("clump " + bad);
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Catch::Contains(bad + ":3:7: radius -0.01 is negative"));
}

TEST_CASE("repose stl reports a mesh and refuses a broken one", "[verbs]") {
  const std::string good = temp("tetra.stl");
  std::ofstream(good) << "solid t\n"
                         "facet normal 0 0 0\n outer loop\n  vertex 0 0 0\n  vertex 0 1 0\n  vertex 1 0 0\n endloop\nendfacet\n"
                         "facet normal 0 0 0\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 0 1\n endloop\nendfacet\n"
                         "facet normal 0 0 0\n outer loop\n  vertex 0 0 0\n  vertex 0 0 1\n  vertex 0 1 0\n endloop\nendfacet\n"
                         "facet normal 0 0 0\n outer loop\n  vertex 1 0 0\n  vertex 0 1 0\n  vertex 0 0 1\n endloop\nendfacet\n"
                         "endsolid t\n";
  Run r = run("stl " + good);
  CHECK(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("triangles    4"));
  CHECK_THAT(r.output, Catch::Contains("watertight   yes"));
  r = run("stl " + good + " --json");
  CHECK(nlohmann::json::parse(r.output)["watertight"] == true);

  const std::string broken = temp("broken.stl");
  std::ofstream(broken, std::ios::binary) << std::string(84, '\0').replace(80, 1, "\x05");
  r = run("stl " + broken);
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Catch::Contains("announces 5 triangles"));
}
