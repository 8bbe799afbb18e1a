// `repose heap-angle` on a heap written as CSV: text, JSON and PNG outputs, and its errors.
#include <catch2/catch.hpp>

#include "tests/cli_support.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <sys/wait.h>

#include "geometry/sphere_csv.h"
#include "synthetic_heaps.h"

namespace {

using Run = repose::test::CliRun;
Run run(const std::string& arguments) { return repose::test::run_repose(arguments); }

// The number printed right after `label` in text.
double number_after(const std::string& text, const std::string& label) {
  const size_t at = text.find(label);
  REQUIRE(at != std::string::npos);
  return std::stod(text.substr(at + label.size()));
}

std::string temp(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("repose_verbs_" + name)).string();
}

}  // namespace

TEST_CASE("repose heap-angle measures a cone and writes JSON and PNG", "[verbs]") {
  const std::string csv = temp("cone.csv"), json = temp("cone.json"), png = temp("cone.png");
  repose::write_sphere_csv(csv, repose::test::cone_shell(0.2, 28.0, 0.005));
  std::filesystem::remove(json);
  std::filesystem::remove(png);
  const Run r = run("heap-angle " + csv + " --view x --png " + png + " --json " + json + " --axisymmetric");
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(std::abs(number_after(r.output, "mean angle") - 28.0) < 0.5);
  CHECK_THAT(r.output, Catch::Contains("8 of 8 sectors"));
  CHECK(std::filesystem::file_size(png) > 1000);
  std::ifstream in(json);
  std::stringstream text;
  text << in.rdbuf();
  const nlohmann::json j = nlohmann::json::parse(text.str());
  CHECK(std::abs(j["mean_deg"].get<double>() - 28.0) < 0.5);
  CHECK(j["axisymmetric"].is_object());
}

TEST_CASE("repose heap-angle errors name the file and exit non-zero", "[verbs]") {
  const std::string bad = temp("bad_heap.csv");
  std::ofstream(bad) << "x,y,z,radius\n0,0,0,0.01\n1,2\n";
  Run r = run("heap-angle " + bad);
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Catch::Contains(bad + ":3:4: expected 4 fields as in the header, found 2"));
  r = run("heap-angle " + bad + " --view z");
  CHECK(r.status != 0);
  r = run("heap-angle /nonexistent/heap.csv");
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Catch::Contains("/nonexistent/heap.csv: cannot open file"));
}
