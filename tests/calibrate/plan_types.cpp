// The cabbage study's chain as plans, each on the cheap drop test (~0.2 s a run): a steepest-ascent
// path, a factor held in the optimisation, two rigs (several responses; calibrate on one, verify
// on another), a raised budget that resumes, and --check's cost and precision.
#include <catch2/catch.hpp>

#include "calibrate_support.h"

using namespace repose;

namespace {

std::string drop_plan(const std::string& mode_and_design, const std::string& extra = "") {
  return "[campaign]\nexperiment = \"drop\"\ncase = \"" + test::drop_case_path() + "\"\n" + extra +
         "\n[response]\nname = \"restitution\"\nmeasured = 0.44\nmeasured_sd = 0.02\nmeasured_n = 25\ntolerance = 0.01\n\n"
         "[set]\n\"experiment.drop_height\" = 0.1\n\"simulation.rayleigh_fraction\" = 0.03\n\n"
         "[[factor]]\nname = \"e\"\nkey = \"interaction.stalk/steel.restitution\"\nlow = 0.3\nhigh = 0.6\n\n" +
         mode_and_design;
}

const std::string kG = "[[factor]]\nname = \"G\"\nkey = \"material.stalk.shear_modulus\"\nlow = 0.5e6\nhigh = 2.0e6\n\n";

nlohmann::json run_plan(const std::string& name, const std::string& plan, int expected_status, std::string* output = nullptr) {
  std::string dir = test::scratch_dir(name);
  test::write_text(dir + "/plan.toml", plan);
  auto run = test::run_repose("calibrate " + dir + "/plan.toml --out " + dir + "/out --jobs 2 --quiet");
  INFO(run.output);
  REQUIRE(run.status == expected_status);
  if (output) *output = run.output;
  return nlohmann::json::parse(test::read_text_file(dir + "/out/summary.json"));
}

}  // namespace

TEST_CASE("a steepest-ascent path runs its points, chooses the best without a model, and its verification decides") {
  // e and G from (0.3, 0.5 MPa) to (0.6, 2 MPa) in 4 points, 2 fills each: restitution follows e
  // (0.30, 0.40, 0.50, 0.60), so the second point is nearest 0.44 and verifies at ~0.40: 9 %
  // off, far beyond 1 % + 2 standard errors of 0.004: contradicted, exit code 3.
  std::string out;
  auto s = run_plan("path", drop_plan(kG + "[design]\ntype = \"path\"\nlevels = 4\nreplicates = 2\n\n[verification]\nruns = 2\n"),
                    3, &out);
  CHECK(s["method"] == "steepest-ascent path");
  CHECK(int(s["simulations"]) == 10);
  CHECK(double(s["parameters"]["e"]["value"]) == Approx(0.4));
  CHECK(double(s["parameters"]["G"]["value"]) == Approx(1.0e6));
  CHECK(s["verification"]["agreement"] == "contradicted");
  CHECK(s["target_reached"] == false);
  CHECK(out.find("target NOT reached: the verification contradicts the calibration") != std::string::npos);
  CHECK(s["posterior"].is_null());  // a path fits no model
  bool has_path_figure = false;
  for (const auto& f : s["figures"]) has_path_figure = has_path_figure || f == "path.png";
  CHECK(has_path_figure);
}

TEST_CASE("a factor held in the optimisation is read from the campaign's own runs") {
  // The CCD varies G; the optimisation holds it at 1 MPa, as the cabbage study held e at 0.42.
  auto s = run_plan("fixed", drop_plan(kG + "[design]\ntype = \"ccd\"\ncentre = 3\nmodel = \"quadratic\"\nfix = { G = 1.0e6 }\n\n"
                                            "[verification]\nruns = 2\n"),
                    0);
  CHECK(double(s["parameters"]["G"]["value"]) == 1.0e6);
  CHECK(double(s["parameters"]["e"]["value"]) == Approx(0.44).epsilon(0.03));
  CHECK(s["verification"]["agreement"] == "confirmed");
}

TEST_CASE("two rigs: several responses calibrate together, or one rig calibrates and another verifies") {
  const std::string rig = "\n[[rig]]\nname = \"high\"\ncase = \"" + test::drop_case_path() +
                          "\"\nset = { \"experiment.drop_height\" = 0.2, \"simulation.rayleigh_fraction\" = 0.03 }\n";
  const std::string sweep = "[design]\ntype = \"sweep\"\nlevels = 4\ndegree = 1\n\n[verification]\nruns = 2\n";
  // Both rigs calibrate: the sweep runs on each, both are verified.
  std::string both = drop_plan(sweep, rig);
  both += "\n[[response]]\nname = \"restitution\"\nrig = \"high\"\nmeasured = 0.44\nmeasured_sd = 0.02\nmeasured_n = 25\n";
  both.replace(both.find("[response]"), 10, "[[response]]");
  std::string dir = test::scratch_dir("two_rigs");
  test::write_text(dir + "/plan.toml", both);
  auto run = test::run_repose("calibrate " + dir + "/plan.toml --out " + dir + "/out --jobs 2 --quiet");
  INFO(run.output);
  auto s = nlohmann::json::parse(test::read_text_file(dir + "/out/summary.json"));
  CHECK(int(s["simulations"]) == 12);  // 4 levels and 2 verification runs on each rig
  REQUIRE(s["verifications"].size() == 2);
  CHECK(s["verifications"][1]["response"] == "restitution@high");
  CHECK(run.status == (s["target_reached"] == true ? 0 : 3));
  CHECK(test::database_rows(dir + "/out/campaign.sqlite").count("design-002-r0@high"));
  CHECK(test::read_text_file(dir + "/out/runs_high.csv").find("design-002-r0@high") != std::string::npos);

  // Calibrate on the campaign's case, verify only on the other rig (the box, then the cylinder).
  std::string verify_only = drop_plan(sweep, rig);
  verify_only += "\n[[response]]\nname = \"restitution\"\nrig = \"high\"\nrole = \"verify\"\nmeasured = 0.44\n"
                 "measured_sd = 0.02\nmeasured_n = 25\n";
  verify_only.replace(verify_only.find("[response]"), 10, "[[response]]");
  auto v = run_plan("verify_rig", verify_only, 0);
  CHECK(int(v["simulations"]) == 6);  // 4 levels on the campaign's case, 2 verification runs on the other rig
  REQUIRE(v["verifications"].size() == 1);
  CHECK(v["verifications"][0]["response"] == "restitution@high");
  CHECK(v["verifications"][0]["agreement"] == "confirmed");
}

TEST_CASE("a raised budget resumes the same campaign") {
  // Two factors from 3 start runs and a tolerance of 0.05 %: the loop cannot meet it at once.
  std::string plan = drop_plan(kG + "[adaptive]\ninitial = 3\nbudget = 3\n\n[verification]\nruns = 1\n", "mode = \"adaptive\"\n");
  plan.replace(plan.find("tolerance = 0.01"), 16, "tolerance = 0.0005");
  std::string dir = test::scratch_dir("budget");
  test::write_text(dir + "/plan.toml", plan);
  auto first = test::run_repose("calibrate " + dir + "/plan.toml --out " + dir + "/out --jobs 1 --quiet");
  INFO(first.output);
  REQUIRE(first.status == 3);
  const auto rows = test::database_rows(dir + "/out/campaign.sqlite");
  CHECK(rows.size() == 4);  // 3 loop runs + 1 verification
  plan.replace(plan.find("budget = 3"), 10, "budget = 5");
  test::write_text(dir + "/plan.toml", plan);
  auto second = test::run_repose("calibrate " + dir + "/plan.toml --out " + dir + "/out --jobs 1 --quiet");
  INFO(second.output);
  CHECK(second.output.find("another version of the plan") == std::string::npos);
  const auto after = test::database_rows(dir + "/out/campaign.sqlite");
  for (const auto& [id, row] : rows) CHECK(after.at(id) == row);  // kept, not rerun
  CHECK(after.count("loop-004"));
  auto s = nlohmann::json::parse(test::read_text_file(dir + "/out/summary.json"));
  CHECK(int(s["loop_runs"]) >= 4);
  CHECK(second.output.find("(" + std::to_string(after.size() - rows.size()) + " run now)") != std::string::npos);
}

TEST_CASE("more verification runs resume a design campaign, keeping what it ran") {
  std::string plan = drop_plan("[design]\ntype = \"sweep\"\nlevels = 3\ndegree = 1\n\n[verification]\nruns = 1\n");
  std::string dir = test::scratch_dir("more_verify");
  test::write_text(dir + "/plan.toml", plan);
  auto first = test::run_repose("calibrate " + dir + "/plan.toml --out " + dir + "/out --jobs 1 --quiet");
  INFO(first.output);
  REQUIRE((first.status == 0 || first.status == 3));
  const auto rows = test::database_rows(dir + "/out/campaign.sqlite");
  CHECK(rows.size() == 4);  // 3 levels + 1 verification run
  plan.replace(plan.find("runs = 1"), 8, "runs = 3");
  test::write_text(dir + "/plan.toml", plan);
  auto second = test::run_repose("calibrate " + dir + "/plan.toml --out " + dir + "/out --jobs 1 --quiet");
  INFO(second.output);
  CHECK(second.output.find("another version of the plan") == std::string::npos);
  CHECK(second.output.find("(2 run now)") != std::string::npos);
  const auto after = test::database_rows(dir + "/out/campaign.sqlite");
  CHECK(after.size() == 6);
  for (const auto& [id, row] : rows) CHECK(after.at(id) == row);  // kept, not rerun
  auto s = nlohmann::json::parse(test::read_text_file(dir + "/out/summary.json"));
  CHECK(s["verifications"][0]["runs"].size() == 3);
}

TEST_CASE("calibrate --check prints the plan's cost and flags a tolerance the budget cannot reach") {
  std::string plan = drop_plan("[design]\ntype = \"sweep\"\nlevels = 4\ndegree = 1\n\n[verification]\nruns = 2\n");
  plan.replace(plan.find("tolerance = 0.01"), 16, "tolerance = 0.01\nnoise_sd = 0.05");
  std::string dir = test::scratch_dir("check");
  test::write_text(dir + "/plan.toml", plan);
  auto run = test::run_repose("calibrate " + dir + "/plan.toml --check --out " + dir + "/out");
  INFO(run.output);
  CHECK(run.status == 0);
  CHECK(run.output.find("cost: at most 6 simulations") != std::string::npos);
  CHECK(run.output.find("particles x") != std::string::npos);  // the probe's time estimate
  // sd 0.05 over 2 runs: a standard error of 0.036 against a tolerance of 0.0044, of which the lab's
  // 0.004 leaves sqrt(0.0044^2 - 0.004^2) = 0.00183 to the runs: (0.05 / 0.00183)^2 = 745 of them.
  CHECK(run.output.find("UNREACHABLE with verification.runs = 2: raise it to 745") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir + "/out"));  // nothing written
  // The lab's own standard error above the tolerance: no number of runs helps.
  plan.replace(plan.find("measured_n = 25"), 15, "measured_n = 4");
  test::write_text(dir + "/plan.toml", plan);
  auto lab = test::run_repose("calibrate " + dir + "/plan.toml --check --out " + dir + "/out");
  CHECK(lab.output.find("UNREACHABLE: the lab's own standard error exceeds the tolerance") != std::string::npos);
}
