// The measured-data CSV of `repose diagnose`: good rows load; every mistake names file, line,
// column and what is wrong.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "diagnosis/measured_data.h"

using namespace repose;
namespace fs = std::filesystem;

namespace {

fs::path data_dir() {
  fs::path d = fs::temp_directory_path() / "repose_measured_data";
  fs::create_directories(d);
  fs::copy_file(fs::path(REPOSE_SOURCE_DIR) / "cases/drop_sphere.toml", d / "drop.toml",
                fs::copy_options::overwrite_existing);
  fs::copy_file(fs::path(REPOSE_SOURCE_DIR) / "cases/diagnosis/foam_ball_roll.toml", d / "roll.toml",
                fs::copy_options::overwrite_existing);
  return d;
}

std::string error_of(const std::string& csv) {
  fs::path f = data_dir() / "data.csv";
  std::ofstream(f) << csv;
  try {
    read_measured_data(f.string());
  } catch (const DataError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("measured data: rows with overrides, replicates, sigma and series load", "[diagnosis]") {
  fs::path f = data_dir() / "good.csv";
  std::ofstream(f) << "case,set:experiment.drop_height,measure,value,replicate,sigma,t\n"
                      "drop.toml,0.3,rebound_height,0.0515,1,0.002,\n"
                      "drop.toml,0.3,rebound_height,0.0521,2,0.002,\n"
                      "drop.toml,0.5,rebound_height,0.0874,1,,\n"
                      "drop.toml,0.5,height,0.41,1,,0.1\n";
  MeasuredData d = read_measured_data(f.string());
  REQUIRE(d.rows.size() == 4);
  CHECK(d.rows[0].sets.size() == 1);
  CHECK(d.rows[0].sets[0].key == "experiment.drop_height");
  CHECK(d.rows[1].replicate == 2);
  CHECK(d.rows[1].sigma.value() == Approx(0.002));
  CHECK_FALSE(d.rows[2].sigma.has_value());
  CHECK(d.rows[3].t.value() == Approx(0.1));
  CHECK(d.rows[3].line == 5);
}

TEST_CASE("measured data: mistakes are reported with file, line and column", "[diagnosis]") {
  std::string head = "case,set:experiment.drop_height,measure,value,replicate\n";
  std::string e = error_of(head + "drop.toml,0.3,rebound_height,abc,1\n");
  INFO(e);
  CHECK(e.find("data.csv:2:30: column 'value'") != std::string::npos);
  CHECK(e.find("not a number") != std::string::npos);

  e = error_of(head + "drop.toml,0.3,rebound_height,51.5,1\n");  // millimetres
  CHECK(e.find("data.csv:2:") != std::string::npos);
  CHECK(e.find("millimetres") != std::string::npos);

  e = error_of(head + "drop.toml,0.3,bounce,0.05,1\n");
  CHECK(e.find("column 'measure'") != std::string::npos);
  CHECK(e.find("unknown measure 'bounce'") != std::string::npos);

  e = error_of(head + "nowhere.toml,0.3,rebound_height,0.05,1\n");
  CHECK(e.find("data.csv:2:1: column 'case'") != std::string::npos);

  e = error_of("case,set:experiment.drop_hieght,measure,value,replicate\ndrop.toml,0.3,rebound_height,0.05,1\n");
  CHECK(e.find("data.csv:2:11: column 'set:experiment.drop_hieght'") != std::string::npos);

  e = error_of(head + "drop.toml,0.3,height,0.05,1\n");
  CHECK(e.find("time series") != std::string::npos);

  e = error_of("case,measure,value\ndrop.toml,rebound_height,0.05\n");
  CHECK(e.find("missing column 'replicate'") != std::string::npos);

  // A rolling distance in millimetres: 474 m from S = 0.2 m on 10 deg, farther than rolling
  // friction 0.002 allows (17.4 m); 0.474 m loads.
  std::string roll = "case,set:experiment.slope_distance,measure,value,replicate\n";
  e = error_of(roll + "roll.toml,0.2,roll_distance,474,1\n");
  INFO(e);
  CHECK(e.find("data.csv:2:") != std::string::npos);
  CHECK(e.find("millimetres") != std::string::npos);
  CHECK(error_of(roll + "roll.toml,0.2,roll_distance,0.474,1\n").empty());
}
