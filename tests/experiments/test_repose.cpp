// Angle-of-repose rigs end to end: fill, settle, lift, settle, measure.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>

#include "case/case_loader.h"
#include "experiments/repose.h"
#include "plot/chart.h"

using namespace repose;

TEST_CASE("the bucket rig with a fast gate (454 spheres) gives a sensible angle of repose", "[experiments][repose]") {
  // The shipped bucket case (454 spheres), filled for 1 s and the gate pulled at 0.25 m/s.
  CaseSpec spec = load_case(std::string(REPOSE_SOURCE_DIR) + "/cases/experiments/repose_bucket_spheres.toml",
                            {{"wall.gate.motion.start", "1.0"},
                             {"wall.gate.motion.stop", "2.8"},
                             {"wall.gate.motion.velocity", "[0.0, 0.0, 0.25]"},
                             {"experiment.lift_end", "2.8"},
                             {"experiment.max_time", "10"}});
  ReposeResult r = run_repose(spec);
  INFO("angle " << r.angle_deg << " deg, heap " << r.heap.heap_height << " m, " << r.particles_measured
                << " particles left, settled at " << r.settle_time << " s");
  // Frictional spheres (mu_s 0.62, mu_r 0.02 between them) hold a slope between the angle of
  // rolling spheres (~20 deg) and that of rough grains (~40 deg).
  CHECK(r.angle_deg > 15);
  CHECK(r.angle_deg < 40);
  CHECK(r.heap.right.valid);
  CHECK(r.particles_measured < 454);  // some ran out through the gate
  CHECK(r.particles_measured > 200);
  CHECK(r.settle_time >= 2.8);
  REQUIRE(!r.wall_forces.rows.empty());
  // The floor carries the weight of what stays in the bucket once settled (wall_forces.csv).
  const auto& last = r.wall_forces.rows.back();
  double floor_fz = 0;
  for (const auto& w : last)
    if (w.name == "floor") floor_fz = w.fz;
  CHECK(floor_fz < 0);
}

TEST_CASE("repose: a lifted wall without a stop time needs lift_end", "[experiments][repose]") {
  CaseSpec spec = load_case(std::string(REPOSE_SOURCE_DIR) + "/cases/experiments/repose_bucket_spheres.toml",
                            {{"wall.gate.motion.stop", "1e31"}, {"experiment.lift_end", "0"}});
  CHECK_THROWS_WITH(run_repose(spec), Catch::Contains("lift_end"));
}

TEST_CASE("repose: visible_from hides part of one front view only", "[experiments][repose]") {
  const std::string box = std::string(REPOSE_SOURCE_DIR) + "/cases/experiments/repose_box_spheres.toml";
  CHECK_NOTHROW(load_case(box, {{"experiment.visible_from", "-0.3"}}));
  // With several views or the 3D fit, a fixed window in one picture hides nothing sensible.
  CHECK_THROWS_WITH(load_case(std::string(REPOSE_SOURCE_DIR) + "/cases/experiments/repose_cylinder_spheres.toml",
                              {{"experiment.visible_from", "-0.3"}}),
                    Catch::Contains("visible_from") && Catch::Contains("views = 1"));
}

// The bottomless cylinder clears the heap of spheres half way through its lift; with
// end_when_clear (the default) the heap is measured once it has settled there, without
// simulating the rest of the lift, and reads the same angle.
TEST_CASE("repose: the lift ends early once the lifted wall is clear and the heap has settled", "[experiments][repose]") {
  std::string path = std::string(REPOSE_SOURCE_DIR) + "/cases/experiments/repose_cylinder_spheres.toml";
  ReposeResult early = run_repose(load_case(path));
  ReposeResult full = run_repose(load_case(path, {{"experiment.end_when_clear", "false"}}));
  INFO("early: settled at " << early.settle_time << " s, " << early.angle_deg << " deg; full lift: "
                            << full.settle_time << " s, " << full.angle_deg << " deg");
  CHECK(full.settle_time >= 30.0);  // lift_end
  CHECK(early.settle_time < 20.0);
  // Below settle_energy the heap only creeps: a tenth of a degree in the 15 s it is not simulated.
  CHECK(std::abs(early.angle_deg - full.angle_deg) < 0.5);
}

// What the console prints first, repose.json's angle and heap.png's title are one headline: the
// angle the experiment reports, and how it was measured (the slope on heap_side, or the mean of
// the views' slopes). The slot heap is the cheapest rig (a second of CPU).
TEST_CASE("repose: the console, repose.json and heap.png state the same headline angle", "[experiments][repose]") {
  Chart::keep_records();
  const std::string path = std::string(REPOSE_SOURCE_DIR) + "/cases/diagnosis/slot_heap.toml";
  struct Rig {
    std::vector<CaseOverride> sets;
    std::string measured_as;
  };
  for (const Rig& rig : {Rig{{}, "the right slope"},
                         Rig{{{"experiment.heap_side", "both"}, {"experiment.views", "4"}}, "the mean of 4 views' slopes"}}) {
    const CaseSpec spec = load_case(path, rig.sets);
    ExperimentOutcome o = repose_experiment().run(spec, {});
    const double angle = o.values.at("angle");
    const std::string headline = printf_text("%.2f deg (%s", angle, rig.measured_as.c_str());
    const auto dir = std::filesystem::temp_directory_path() / ("repose_test_headline_" + std::to_string(rig.sets.size()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    write_outcome(o, "repose.json", dir.string());
    const ChartRecord picture = Chart::recorded((dir / "heap.png").string());
    INFO("console: " << o.lines.front() << "\npicture: " << picture.title);
    CHECK(o.lines.front().find("angle of repose " + headline) != std::string::npos);
    CHECK(picture.title == "Angle of repose " + headline + ")");
    CHECK(o.json["angle_deg"].get<double>() == angle);
    CHECK(o.json["angle_measured_as"] == rig.measured_as);
    std::filesystem::remove_all(dir);
  }
}

// A heap still moving at max_time is measured as it stands (status not settled); its picture
// says so in the title, where a reader of the picture alone looks.
TEST_CASE("repose: heap.png of a heap measured unsettled says so in its title", "[experiments][repose]") {
  Chart::keep_records();
  const std::string path = std::string(REPOSE_SOURCE_DIR) + "/cases/diagnosis/slot_heap.toml";
  const CaseSpec spec = load_case(path, {{"experiment.max_time", "0.6"}});  // the gate lifts at 0.55 s
  ExperimentRun measure_as_it_stands;
  measure_as_it_stands.strict = false;  // as `repose experiment` runs it
  ExperimentOutcome o = repose_experiment().run(spec, measure_as_it_stands);
  REQUIRE(o.status == OutcomeStatus::NotSettled);
  const auto dir = std::filesystem::temp_directory_path() / "repose_test_unsettled_title";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  write_outcome(o, "repose.json", dir.string());
  const ChartRecord picture = Chart::recorded((dir / "heap.png").string());
  const double t = o.json["settle_time"].get<double>();
  INFO("title: " << picture.title);
  CHECK(t >= 0.6);
  CHECK(picture.title.find(printf_text(", not settled at %.3g s", t)) != std::string::npos);
  std::filesystem::remove_all(dir);

  std::filesystem::create_directories(dir);
  ExperimentOutcome settled = repose_experiment().run(load_case(path), {});
  REQUIRE(settled.status == OutcomeStatus::Measured);
  write_outcome(settled, "repose.json", dir.string());
  CHECK(Chart::recorded((dir / "heap.png").string()).title.find("not settled") == std::string::npos);
  std::filesystem::remove_all(dir);
}
