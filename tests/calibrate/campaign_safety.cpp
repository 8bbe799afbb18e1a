// A campaign cannot mix inputs or lose runs: the plan's identity is the base case as parsed plus
// every file it reads (comments do not count, an edited template does), a second campaign on a
// busy database is refused, and a run that cannot be stored ends the campaign cleanly with the
// other finished runs kept.
#include <catch2/catch.hpp>
#include <filesystem>

#include <chrono>
#include <thread>

#include "calibrate/plan.h"
#include "calibrate/run_store.h"
#include "calibrate_support.h"

using namespace repose;
using namespace repose::calibrate;

namespace {

// A drop case of a two-sphere clump read from a template CSV beside it, and a plan over it.
void write_clump_campaign(const std::string& dir, const std::string& case_comment, const std::string& second_sphere) {
  test::write_text(dir + "/pair.csv", "x,y,z,radius\n-0.004,0,0,0.005\n" + second_sphere + "\n");
  std::string text = test::read_text_file(test::drop_case_path());
  auto at = text.find("[[sphere]]");
  REQUIRE(at != std::string::npos);
  text = case_comment + text.substr(0, at) +
         "[[template]]\nname = \"pair\"\nfile = \"pair.csv\"\n\n"
         "[[clump]]\ntemplate = \"pair\"\nmaterial = \"stalk\"\nposition = [0.0, 0.0, 0.305]\n\n" +
         text.substr(text.find("[[wall]]"));
  test::write_text(dir + "/case.toml", text);
  std::string plan = test::small_ccd_plan();
  plan.replace(plan.find(test::drop_case_path()), test::drop_case_path().size(), dir + "/case.toml");
  test::write_text(dir + "/plan.toml", plan);
}

std::string canonical(const std::string& dir) { return canonical_plan_text(load_plan(dir + "/plan.toml")); }

}  // namespace

TEST_CASE("a plan's identity: the case as parsed and its files by content, not its comments") {
  std::string dir = test::scratch_dir("identity");
  write_clump_campaign(dir, "", "0.004,0,0,0.005");
  const std::string first = canonical(dir);
  write_clump_campaign(dir, "# a comment-only edit\n# of the base case\n", "0.004,0,0,0.005");
  CHECK(plan_hash(canonical(dir)) == plan_hash(first));
  // The same template with another second sphere: another geometry, another plan.
  write_clump_campaign(dir, "", "0.004,0,0,0.004");
  std::string edited = canonical(dir);
  CHECK(plan_hash(edited) != plan_hash(first));
  CHECK(describe_plan_change(first, edited).find("# file pair.csv fnv1a") != std::string::npos);
  // A value of the case: named as it was parsed.
  write_clump_campaign(dir, "", "0.004,0,0,0.005");
  std::string text = test::read_text_file(dir + "/case.toml");
  text.replace(text.find("static_friction = 0.31"), 22, "static_friction = 0.32");
  test::write_text(dir + "/case.toml", text);
  std::string change = describe_plan_change(first, canonical(dir));
  INFO(change);
  CHECK(change.find("`interaction.0.static_friction = 0.31` -> `interaction.0.static_friction = 0.32`") != std::string::npos);
}

TEST_CASE("a factor's value in the base case is no run's: editing it keeps the campaign") {
  // The shipped drop case gives the stalk-steel restitution (0.44) that factor e sets in every run:
  // a case that ships another value (as the cabbage cases took their calibrated ones) is the same plan.
  std::string dir = test::scratch_dir("pinned");
  write_clump_campaign(dir, "", "0.004,0,0,0.005");
  const CampaignPlan first = load_plan(dir + "/plan.toml");
  std::string text = test::read_text_file(dir + "/case.toml");
  text.replace(text.find("restitution = 0.44"), 18, "restitution = 0.61");
  test::write_text(dir + "/case.toml", text);
  const CampaignPlan edited = load_plan(dir + "/plan.toml");
  CHECK(plan_hash(canonical_plan_text(edited)) == plan_hash(canonical_plan_text(first)));
  CHECK(canonical_plan_text_as_given(edited) != canonical_plan_text_as_given(first));
  // A database whose plan row was written before the factors were pinned (the base value hashed
  // in) is adopted, its row rewritten; one whose plan differs elsewhere is still refused.
  const std::string db = dir + "/campaign.sqlite";
  { RunStore store(db, first, true); }
  const std::string given = canonical_plan_text_as_given(first);
  REQUIRE(test::sql_exec(db, "UPDATE plan SET hash = ?, canonical = ?", {plan_hash(given), given}));
  CHECK_NOTHROW(RunStore(db, first, false));
  CHECK(test::sql_text(db, "SELECT hash FROM plan") == plan_hash(canonical_plan_text(first)));
  REQUIRE(test::sql_exec(db, "UPDATE plan SET hash = 'f00d', canonical = 'another plan'"));
  CHECK_THROWS_WITH(RunStore(db, first, false), Catch::Contains("another version of the plan"));
}

TEST_CASE("a second campaign on a busy database is refused, the first finishes") {
  std::string dir = test::scratch_dir("busy");
  test::write_text(dir + "/plan.toml", test::small_ccd_plan());
  pid_t first = test::spawn_repose({"calibrate", dir + "/plan.toml", "--out", dir + "/out", "--jobs", "1", "--quiet"},
                                   dir + "/first.log");
  for (int i = 0; i < 2000 && test::count_runs(dir + "/out/campaign.sqlite") < 1; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  // Its database from another folder; its folder with another database (each would spoil the
  // first's runs or its report).
  auto second = test::run_repose("calibrate " + dir + "/plan.toml --out " + dir + "/out2 --db " + dir +
                                 "/out/campaign.sqlite --jobs 1 --quiet");
  auto third = test::run_repose("calibrate " + dir + "/plan.toml --out " + dir + "/out --db " + dir +
                                "/other.sqlite --jobs 1 --quiet");
  int status = 0;
  ::waitpid(first, &status, 0);
  INFO(second.output);
  CHECK(second.status == 2);
  CHECK(second.output.find("is in use by another campaign (process " + std::to_string(first)) != std::string::npos);
  CHECK(second.output.find("another --db") != std::string::npos);
  INFO(third.output);
  CHECK(third.status == 2);
  CHECK(third.output.find("/out is in use by process " + std::to_string(first) + " (") != std::string::npos);
  CHECK(third.output.find("calibrate") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir + "/other.sqlite"));
  INFO(test::read_text_file(dir + "/first.log"));
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  CHECK(test::count_runs(dir + "/out/campaign.sqlite") == 13);
}

TEST_CASE("a run that cannot be stored ends the campaign cleanly, every other finished run is kept") {
  std::string dir = test::scratch_dir("insert_fails");
  test::write_text(dir + "/plan.toml", test::small_ccd_plan());
  const std::string db = dir + "/out/campaign.sqlite";
  { RunStore make(db, load_plan(dir + "/plan.toml"), false); }  // the database, as the campaign makes it
  // The database refuses one run's row, as a full disk or a locked file would.
  sqlite3* handle = nullptr;
  REQUIRE(sqlite3_open(db.c_str(), &handle) == SQLITE_OK);
  REQUIRE(sqlite3_exec(handle, "CREATE TRIGGER refuse BEFORE INSERT ON runs WHEN NEW.run_id = 'design-004-r0' "
                               "BEGIN SELECT RAISE(ABORT, 'database or disk is full (test)'); END;",
                       nullptr, nullptr, nullptr) == SQLITE_OK);
  sqlite3_close(handle);
  auto failed = test::run_repose("calibrate " + dir + "/plan.toml --out " + dir + "/out --jobs 2 --quiet");
  INFO(failed.output);
  CHECK(failed.status == 1);  // an exit, not std::terminate's SIGABRT
  CHECK(failed.output.find("design-004-r0 finished but could not be stored") != std::string::npos);
  CHECK(failed.output.find("disk is full (test)") != std::string::npos);
  CHECK(failed.output.find("every finished run is kept") != std::string::npos);
  const int kept = test::count_runs(db);
  CHECK(kept >= 3);  // the runs before it and those in flight beside it
  // Once the database takes rows again, the campaign resumes and runs only what is missing.
  REQUIRE(sqlite3_open(db.c_str(), &handle) == SQLITE_OK);
  sqlite3_exec(handle, "DROP TRIGGER refuse", nullptr, nullptr, nullptr);
  sqlite3_close(handle);
  auto resumed = test::run_repose("calibrate " + dir + "/plan.toml --out " + dir + "/out --jobs 2");
  INFO(resumed.output);
  CHECK(resumed.status == 0);
  CHECK(resumed.output.find(std::to_string(kept) + " of 11 runs already in") != std::string::npos);
  CHECK(test::count_runs(db) == 13);
}

TEST_CASE("an unreachable target and a campaign without verification are said as such") {
  std::string dir = test::scratch_dir("unreachable");
  std::string plan = test::small_ccd_plan();
  plan.replace(plan.find("measured = 0.44"), 15, "measured = 0.90");  // e <= 0.55 cannot rebound that high
  plan.replace(plan.find("[verification]\nruns = 2"), 23, "[verification]\nruns = 0");
  test::write_text(dir + "/plan.toml", plan);
  auto run = test::run_repose("calibrate " + dir + "/plan.toml --out " + dir + "/out --jobs 2 --quiet");
  INFO(run.output);
  CHECK(run.status == 3);  // target not reached
  CHECK(run.output.find("TARGET REACHED") == std::string::npos);
  CHECK(run.output.find("the model does not reach the measured value within the tolerance anywhere in the factor box") !=
        std::string::npos);
  CHECK(run.output.find("target NOT reached: nothing verified (verification.runs = 0)") != std::string::npos);
  auto summary = nlohmann::json::parse(test::read_text_file(dir + "/out/summary.json"));
  CHECK(summary["verification"].is_null());
  CHECK(summary["target_reached"] == false);
  CHECK(summary["model_on_target"] == false);
  CHECK(summary["provenance"]["case_hash"].get<std::string>().size() == 16);
  CHECK(test::read_text_file(dir + "/out/report.md").find("**The model does not put every calibrating response within its "
                                                         "tolerance**") != std::string::npos);
}
