// Bad plans are refused when loaded, before anything runs, with the plan file, line and key.
#include <catch2/catch.hpp>

#include <algorithm>

#include "calibrate/experiment_runner.h"
#include "calibrate/plan.h"
#include "calibrate_support.h"
#include "experiments/registry.h"

using namespace repose;
using namespace repose::calibrate;

namespace {

// Loads `text` as a plan and returns the error message ("" when it loads).
std::string plan_error(const std::string& text, const std::string& name) {
  std::string dir = test::scratch_dir("plan_" + name);
  std::string path = dir + "/plan.toml";
  test::write_text(path, text);
  try {
    load_plan(path);
  } catch (const CaseError& e) {
    return e.what();
  }
  return "";
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  auto at = s.find(from);
  REQUIRE(at != std::string::npos);
  return s.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("a good plan loads and its hash ignores layout and comments") {
  std::string plan = test::small_ccd_plan();
  CHECK(plan_error(plan, "good").empty());
  std::string dir = test::scratch_dir("plan_hash");
  test::write_text(dir + "/a.toml", plan);
  test::write_text(dir + "/b.toml", "# a comment\n" + replace(plan, "measured = 0.44\n", "measured   =   0.44   # lab\n"));
  CampaignPlan a = load_plan(dir + "/a.toml"), b = load_plan(dir + "/b.toml");
  CHECK(plan_hash(canonical_plan_text(a)) == plan_hash(canonical_plan_text(b)));
  CHECK(a.base_seed == 1);  // the case's simulation.seed
  test::write_text(dir + "/c.toml", test::small_ccd_plan("0.6"));
  CampaignPlan c = load_plan(dir + "/c.toml");
  CHECK(describe_plan_change(canonical_plan_text(a), canonical_plan_text(c)) == "factor.0.high: 0.55 -> 0.6");
}

TEST_CASE("an unknown factor key is refused at its plan line") {
  std::string msg = plan_error(replace(test::small_ccd_plan(), "stalk/steel.restitution", "stalk/steel.restitutio"), "key");
  CHECK(msg.find("plan.toml:18: factor.e.key") != std::string::npos);
  CHECK(msg.find("restitutio") != std::string::npos);
  CHECK(msg.find("unknown key") != std::string::npos);
  // A material the case does not have.
  msg = plan_error(replace(test::small_ccd_plan(), "material.stalk.shear_modulus", "material.straw.shear_modulus"), "material");
  CHECK(msg.find("factor.G.key") != std::string::npos);
  CHECK(msg.find("straw") != std::string::npos);
}

TEST_CASE("a reversed range is refused") {
  std::string msg = plan_error(replace(test::small_ccd_plan(), "low = 0.35\nhigh = 0.55", "low = 0.55\nhigh = 0.35"), "range");
  CHECK(msg.find("plan.toml:20: factor.e.high: range reversed") != std::string::npos);
}

TEST_CASE("a design with fewer runs than model terms is refused") {
  // 2^2 factorial + 1 centre point = 5 distinct points for the 6 terms of a quadratic model.
  std::string plan = replace(test::small_ccd_plan(), "type = \"ccd\"\ncentre = 3", "type = \"factorial\"\ncentre = 1");
  std::string msg = plan_error(plan, "terms");
  CHECK(msg.find("design.model: fewer runs than model terms") != std::string::npos);
  CHECK(msg.find("6 terms") != std::string::npos);
  // A sweep with fewer levels than the curve's coefficients.
  std::string sweep = "[campaign]\nexperiment = \"drop\"\ncase = \"" + test::drop_case_path() +
                      "\"\n[response]\nname = \"restitution\"\nmeasured = 0.44\n"
                      "[[factor]]\nname = \"e\"\nkey = \"interaction.stalk/steel.restitution\"\nlow = 0.3\nhigh = 0.6\n"
                      "[design]\ntype = \"sweep\"\nlevels = 3\ndegree = 3\n";
  msg = plan_error(sweep, "sweep");
  CHECK(msg.find("plan.toml:14: design.levels") != std::string::npos);
  CHECK(msg.find("fewer runs than model terms") != std::string::npos);
}

TEST_CASE("a missing response, column or table is named") {
  std::string msg = plan_error(replace(test::small_ccd_plan(), "name = \"restitution\"", "name = \"bounce\""), "response");
  CHECK(msg.find("plan.toml:6: response.name") != std::string::npos);
  CHECK(msg.find("restitution") != std::string::npos);  // lists what the experiment gives

  msg = plan_error(replace(test::small_ccd_plan(), "measured = 0.44\n", ""), "measured");
  CHECK(msg.find("response.measured: missing required value") != std::string::npos);

  // A design table without the column of factor G.
  std::string dir = test::scratch_dir("plan_table");
  test::write_text(dir + "/runs.csv", "e,g\n0.4,1e6\n0.5,1e6\n");
  std::string plan = replace(test::small_ccd_plan(), "type = \"ccd\"\ncentre = 3\nmodel = \"quadratic\"",
                             "type = \"table\"\ntable = \"runs.csv\"\nmodel = \"linear\"");
  test::write_text(dir + "/plan.toml", plan);
  try {
    load_plan(dir + "/plan.toml");
    FAIL("a table without column G loaded");
  } catch (const CaseError& e) {
    std::string m = e.what();
    CHECK(m.find("design.table") != std::string::npos);
    CHECK(m.find("runs.csv:1") != std::string::npos);
    CHECK(m.find("'G'") != std::string::npos);
  }
}

TEST_CASE("bad TOML, an unknown experiment and unknown plan keys are located") {
  std::string msg = plan_error("[campaign]\nexperiment = \"drop\n", "toml");
  CHECK(msg.find("plan.toml:2:") != std::string::npos);
  msg = plan_error(replace(test::small_ccd_plan(), "experiment = \"drop\"", "experiment = \"shear_box\""), "experiment");
  CHECK(msg.find("plan.toml:2: campaign.experiment: unknown experiment 'shear_box'") != std::string::npos);
  msg = plan_error(replace(test::small_ccd_plan(), "centre = 3", "center = 3"), "unknown");
  CHECK(msg.find("design.center: unknown key") != std::string::npos);
}

TEST_CASE("the calibrate verb reports a bad plan with exit code 2 and writes nothing") {
  std::string dir = test::scratch_dir("verb_bad");
  test::write_text(dir + "/plan.toml", replace(test::small_ccd_plan(), "low = 0.35\nhigh = 0.55", "low = 0.55\nhigh = 0.35"));
  auto run = test::run_repose("calibrate " + dir + "/plan.toml --out " + dir + "/out");
  CHECK(run.status == 2);
  CHECK(run.output.find("factor.e.high: range reversed") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir + "/out"));
}

TEST_CASE("the shipped plans load") {
  const std::string cases = std::string(REPOSE_SOURCE_DIR) + "/cases/calibrate/";
  CHECK_NOTHROW(load_plan(cases + "drop_restitution.toml"));
  CHECK_NOTHROW(load_plan(cases + "drop_restitution_adaptive.toml"));
  CHECK_NOTHROW(load_plan(cases + "cabbage_repose_adaptive.toml"));  // on the cabbage box rig
  CampaignPlan cylinder = load_plan(cases + "cabbage_cylinder_adaptive.toml");  // 16 views, seeds per run
  CHECK(cylinder.adaptive.seed_per_run);
}

TEST_CASE("the adaptive loop's seeds are \"same\" or \"per_run\", and per_run changes the plan's hash") {
  const std::string adaptive = "[campaign]\nexperiment = \"drop\"\ncase = \"" + test::drop_case_path() +
                               "\"\nmode = \"adaptive\"\n[response]\nname = \"restitution\"\nmeasured = 0.44\n"
                               "[[factor]]\nname = \"e\"\nkey = \"interaction.stalk/steel.restitution\"\nlow = 0.2\nhigh = 0.8\n"
                               "[adaptive]\nbudget = 10\n";
  CHECK(plan_error(adaptive, "seeds_default").empty());
  CHECK(plan_error(adaptive + "seeds = \"same\"\n", "seeds_same").empty());
  std::string msg = plan_error(adaptive + "seeds = \"fresh\"\n", "seeds_bad");
  INFO(msg);
  CHECK(msg.find("plan.toml:15: adaptive.seeds: expected \"same\"") != std::string::npos);
  std::string dir = test::scratch_dir("plan_seeds");
  test::write_text(dir + "/same.toml", adaptive + "seeds = \"same\"\n");
  test::write_text(dir + "/default.toml", adaptive);
  test::write_text(dir + "/per_run.toml", adaptive + "seeds = \"per_run\"\n");
  const std::string same = canonical_plan_text(load_plan(dir + "/same.toml"));
  CHECK(same == canonical_plan_text(load_plan(dir + "/default.toml")));  // plans from before keep their runs
  CHECK(same != canonical_plan_text(load_plan(dir + "/per_run.toml")));
}

TEST_CASE("every registered experiment is reachable by name") {
  // Every type of the registry, whatever it holds (a new experiment needs no edit here).
  std::vector<std::string> types = repose::experiment_types();
  REQUIRE(types.size() >= 4);
  for (const std::string& name : types) CHECK(find_experiment(name).name == name);
  std::sort(types.begin(), types.end());
  std::string listed;
  for (const std::string& name : types) listed += (listed.empty() ? "" : ", ") + name;
  CHECK_THROWS_WITH(find_experiment("shear_box"), Catch::Contains("registered: " + listed));
}

TEST_CASE("the new plan keys are checked at their lines") {
  const std::string base = test::small_ccd_plan();
  // A held value outside its factor's range, and a held factor on a sweep.
  std::string msg = plan_error(replace(base, "model = \"quadratic\"", "model = \"quadratic\"\nfix = { G = 3.0e6 }"), "fix_range");
  CHECK(msg.find("design.fix.G: 3e+06 lies outside the factor's range") != std::string::npos);
  msg = plan_error(replace(base, "model = \"quadratic\"", "model = \"quadratic\"\nfix = { H = 1.0 }"), "fix_name");
  CHECK(msg.find("no factor named 'H'") != std::string::npos);
  // A path's end outside the range, and a model asked of a path.
  msg = plan_error(replace(base, "type = \"ccd\"\ncentre = 3\nmodel = \"quadratic\"", "type = \"path\"\nlevels = 4\nfrom = { e = 0.2 }"),
                   "path_from");
  CHECK(msg.find("design.from.e: 0.2 lies outside") != std::string::npos);
  msg = plan_error(replace(base, "type = \"ccd\"\ncentre = 3", "type = \"path\"\nlevels = 4"), "path_model");
  CHECK(msg.find("design.model: a path (steepest ascent) fits no model") != std::string::npos);
  // A response on an unknown rig; every response verify-only.
  msg = plan_error(replace(base, "name = \"restitution\"", "name = \"restitution\"\nrig = \"cylinder\""), "rig");
  CHECK(msg.find("response.rig: no [[rig]] named 'cylinder'") != std::string::npos);
  msg = plan_error(replace(base, "name = \"restitution\"", "name = \"restitution\"\nrole = \"verify\""), "verify_only");
  CHECK(msg.find("one must calibrate") != std::string::npos);
  // Per-run seeds need a pilot that measures the noise.
  const std::string adaptive = "[campaign]\nexperiment = \"drop\"\ncase = \"" + test::drop_case_path() +
                               "\"\nmode = \"adaptive\"\n[response]\nname = \"restitution\"\nmeasured = 0.44\n"
                               "[[factor]]\nname = \"e\"\nkey = \"interaction.stalk/steel.restitution\"\nlow = 0.2\nhigh = 0.8\n"
                               "[adaptive]\nbudget = 10\nseeds = \"per_run\"\n";
  CHECK(plan_error(adaptive, "pilot_default").empty());  // 4 fills by default
  msg = plan_error(adaptive + "pilot = 0\n", "pilot_none");
  CHECK(msg.find("adaptive.pilot: seeds = \"per_run\" makes every run noisy") != std::string::npos);
  msg = plan_error(adaptive + "pilot = 1\n", "pilot_one");
  CHECK(msg.find("adaptive.pilot") != std::string::npos);
}

TEST_CASE("the shipped plans for the cabbage study's chain load") {
  const std::string cases = std::string(REPOSE_SOURCE_DIR) + "/cases/calibrate/";
  CampaignPlan path = load_plan(cases + "cabbage_box_path.toml");
  CHECK(path.design.type == "path");
  CHECK(path.design.path_from == std::vector<double>{0.38, 0.1, 0.01});
  CampaignPlan ccd = load_plan(cases + "cabbage_box_ccd.toml");
  REQUIRE(ccd.design.fixed.size() == 1);
  CHECK(ccd.design.fixed[0].second == 0.7956);  // the template's own drop-test restitution (Table 7)
  CHECK(ccd.verified_responses() == std::vector<int>{1});  // the cylinder verifies
  CHECK(ccd.rigs_of(ccd.verified_responses()) == std::vector<int>{1});
  CampaignPlan adaptive = load_plan(cases + "cabbage_repose_adaptive.toml");
  CHECK(adaptive.adaptive.pilot == 4);
  CHECK(adaptive.rigs.size() == 2);
}
