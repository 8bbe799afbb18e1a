// `repose experiment TYPE CASE.toml` end to end: prints the result, writes JSON and CSV.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "../cli_support.h"

namespace fs = std::filesystem;

TEST_CASE("repose experiment slide prints mu_s and writes slide.json, trajectory.csv, wall_forces.csv",
          "[experiments][cli]") {
  fs::path out = fs::temp_directory_path() / "repose_test_experiment_slide";
  fs::remove_all(out);
  auto run = repose::test::run_repose("experiment slide " + std::string(REPOSE_SOURCE_DIR) +
                          "/cases/experiments/slide_four_spheres.toml --quiet --out " + out.string());
  INFO(run.output);
  REQUIRE(run.status == 0);
  CHECK(run.output.find("mu_s = tan(alpha) = 0.3") != std::string::npos);
  auto j = nlohmann::json::parse(std::ifstream(out / "slide.json"));
  CHECK(j["mu_s"].get<double>() == Approx(0.34).margin(0.02));
  CHECK(fs::file_size(out / "trajectory.csv") > 100);
  std::ifstream forces(out / "wall_forces.csv");
  std::string header;
  std::getline(forces, header);
  CHECK(header == "time,plate.fx,plate.fy,plate.fz");
}

TEST_CASE("repose experiment with the wrong type or a bad [experiment] key fails with exit code 2", "[experiments][cli]") {
  auto wrong = repose::test::run_repose("experiment roll " + std::string(REPOSE_SOURCE_DIR) +
                            "/cases/experiments/slide_four_spheres.toml --quiet");
  CHECK(wrong.status == 2);
  CHECK(wrong.output.find("not 'roll'") != std::string::npos);
  auto bad = repose::test::run_repose("experiment slide " + std::string(REPOSE_SOURCE_DIR) +
                          "/cases/experiments/slide_four_spheres.toml --quiet --set experiment.plate=plat");
  CHECK(bad.status == 2);
  CHECK(bad.output.find("experiment.plate") != std::string::npos);
  CHECK(bad.output.find("plate") != std::string::npos);
}
