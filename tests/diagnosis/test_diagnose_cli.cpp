// `repose diagnose` end to end: the files it promises (diagnosis.json with the keys,
// report.md with its figures, PNGs), and a clear error for bad data.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "../cli_support.h"

using namespace repose::test;
namespace fs = std::filesystem;

TEST_CASE("diagnose writes diagnosis.json, report.md and figures", "[diagnosis][cli]") {
  fs::path dir = fs::temp_directory_path() / "repose_diagnose_cli";
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file(fs::path(REPOSE_SOURCE_DIR) / "cases/diagnosis/cabbage_drop.toml", dir / "cabbage_drop.toml");
  std::string csv = (dir / "data.csv").string();
  CliRun synth = run_repose("synth-data " + (dir / "cabbage_drop.toml").string() +
                            " --extension cohesion=3e4 --heights 0.3,0.4,0.5 --replicates 4 --out " + csv);
  INFO(synth.output);
  REQUIRE(synth.status == 0);
  CliRun run = run_repose("diagnose " + csv + " --quiet --candidates cohesion,air_drag --out " + (dir / "out").string());
  INFO(run.output);
  REQUIRE(run.status == 0);
  CHECK(run.output.find("verdict: ") != std::string::npos);
  nlohmann::json j = nlohmann::json::parse(std::ifstream(dir / "out/diagnosis.json"));
  for (const char* key : {"verdict", "cause", "candidates", "heldout_error_baseline", "heldout_error_extended",
                          "gain_percent", "lack_of_fit", "trends", "statements"})
    CHECK(j.contains(key));
  CHECK(j["candidates"].size() == 2);
  for (const auto& c : j["candidates"]) {
    CHECK(c.contains("parameters"));
    CHECK(c.contains("aic"));
    CHECK(c.contains("p"));
  }
  CHECK(fs::exists(dir / "out/report.md"));
  REQUIRE(j["figures"].size() >= 2);
  for (const auto& f : j["figures"]) CHECK(fs::file_size(dir / "out" / f.get<std::string>()) > 1000);
}

TEST_CASE("diagnose reports bad data with file, line and column and writes nothing", "[diagnosis][cli]") {
  fs::path dir = fs::temp_directory_path() / "repose_diagnose_cli_bad";
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file(fs::path(REPOSE_SOURCE_DIR) / "cases/diagnosis/cabbage_drop.toml", dir / "c.toml");
  std::ofstream(dir / "bad.csv") << "case,set:experiment.drop_height,measure,value,replicate\n"
                                    "c.toml,0.3,rebound_height,0.05,1\n"
                                    "c.toml,0.3,rebound_height,5O,2\n";
  CliRun run = run_repose("diagnose " + (dir / "bad.csv").string() + " --out " + (dir / "out").string());
  CHECK(run.status == 2);
  CHECK(run.output.find("bad.csv:3:") != std::string::npos);
  CHECK(run.output.find("not a number") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "out"));

  // One replicate per condition and no sigma: no noise to judge residuals against.
  std::ofstream(dir / "single.csv") << "case,set:experiment.drop_height,measure,value,replicate\n"
                                       "c.toml,0.3,rebound_height,0.05,1\n"
                                       "c.toml,0.4,rebound_height,0.06,1\n";
  run = run_repose("diagnose " + (dir / "single.csv").string() + " --out " + (dir / "out").string());
  CHECK(run.status == 2);
  CHECK(run.output.find("replicate") != std::string::npos);
}

TEST_CASE("diagnose --params takes the calibrated values as given instead of refitting", "[diagnosis][cli]") {
  fs::path dir = fs::temp_directory_path() / "repose_diagnose_cli_params";
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file(fs::path(REPOSE_SOURCE_DIR) / "cases/diagnosis/cabbage_drop.toml", dir / "cabbage_drop.toml");
  std::string csv = (dir / "data.csv").string();
  REQUIRE(run_repose("synth-data " + (dir / "cabbage_drop.toml").string() +
                     " --restitution 0.45 --heights 0.3,0.4,0.5 --replicates 4 --out " + csv)
              .status == 0);
  std::ofstream(dir / "params.toml") << "\"interaction.cabbage/steel.restitution\" = 0.40\n";
  CliRun run = run_repose("diagnose " + csv + " --quiet --candidates air_drag --params " +
                          (dir / "params.toml").string() + " --out " + (dir / "out").string());
  INFO(run.output);
  REQUIRE(run.status == 0);
  CHECK(run.output.find("parameters as given") != std::string::npos);
  nlohmann::json j = nlohmann::json::parse(std::ifstream(dir / "out/diagnosis.json"));
  CHECK(j["baseline"]["parameters"].empty());  // nothing refitted
  // Restitution 0.40 given where the data say 0.45: the baseline misses them.
  CHECK(j["lack_of_fit"][0]["p"].get<double>() < 0.01);
}

TEST_CASE("lack of fit that no tested candidate removes is 'unexplained', with what was and was not tried",
          "[diagnosis][cli]") {
  // The cabbage data hides a velocity-dependent restitution; shape alone cannot be tested
  // without a sigma column, so nothing is tested while the baseline misses (p = 0.00015).
  fs::path dir = fs::temp_directory_path() / "repose_diagnose_unexplained";
  fs::remove_all(dir);
  CliRun run = run_repose("diagnose " + std::string(REPOSE_SOURCE_DIR) +
                          "/cases/diagnosis/cabbage_data.csv --quiet --candidates shape --out " + (dir / "out").string());
  INFO(run.output);
  REQUIRE(run.status == 0);
  CHECK(run.output.find("verdict: unexplained") != std::string::npos);
  CHECK(run.output.find("adequate") == std::string::npos);
  CHECK(run.output.find("tried none; not tested shape (") != std::string::npos);
  CHECK(run.output.find("air_drag") != std::string::npos);  // named among those not asked for
  nlohmann::json j = nlohmann::json::parse(std::ifstream(dir / "out/diagnosis.json"));
  CHECK(j["verdict"] == "unexplained");
  CHECK(j["tried"].empty());
  REQUIRE(j["untested"].size() == 1);
  CHECK(j["untested"][0]["id"] == "shape");
  CHECK(!j["provenance"]["version"].get<std::string>().empty());
  CHECK(j["provenance"]["inputs"][0]["fnv1a"].get<std::string>().size() == 16);
}
