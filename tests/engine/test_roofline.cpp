// The bench's roofline in segments (engine/roofline.h): each segment's kernels against the roofs
// measured right after it, as medians and ranges.
#include <catch2/catch.hpp>
#include <sstream>

#include "engine/backend_factory.h"
#include "engine/bench_bed.h"
#include "engine/roofline.h"
#include "engine_test_support.h"

using namespace repose;

namespace {

// The table's line for `name`, split into words.
std::vector<std::string> row_of(const std::string& table, const std::string& name) {
  std::istringstream lines(table);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string x; words >> x;) w.push_back(x);
    if (!w.empty() && w[0] == name) return w;
  }
  return {};
}

}  // namespace

TEST_CASE("roofline: a kernel's fraction of each roof is taken per segment, as median and range", "[engine][roofline]") {
  Model model = build_model(bench_bed_case(2000));
  Simulation sim(model, make_backend("cpu", -1, 1, KernelVariant{}.workgroup), KernelVariant{}, 50);
  TrafficCounts counts{2000, 8000, 8000, 64};
  const double bytes = kernel_min_bytes("contact_forces", sim.layout(), counts);  // per step
  REQUIRE(bytes > 0);
  // Three segments of 10 steps at 1 ms per step; the copies move 2x, 1x and 4x its bandwidth,
  // the law alone takes 0.3, 0.5 and 0.2 of its time.
  RooflineRun run;
  const double rate = bytes / 1e-3, law[] = {0.3, 0.5, 0.2}, copy[] = {2, 1, 4};
  for (int s = 0; s < 3; ++s) {
    RoofSegment seg;
    seg.profile.steps = 10;
    seg.profile.kernels["contact_forces"] = 0.01;
    seg.roofs = {copy[s] * rate, 2 * copy[s] * rate, law[s] * 1e-3 / counts.contacts};
    run.segments.push_back(seg);
  }
  auto row = row_of(format_roofline(run, sim.layout(), counts), "contact_forces");
  REQUIRE(row.size() == 8);
  CHECK(row[1] == "1.000");                                         // ms per step over the run
  CHECK(row[4] + " " + row[5] == "0.50 (0.25-1.00)");               // of the own copy: 1/2, 1, 1/4
  CHECK(row[6] + " " + row[7] == "0.25 (0.12-0.50)");               // of the DRAM copy, twice as fast
  std::string ceiling = format_law_ceiling(run, sim.layout(), counts);
  CHECK(ceiling.find("per segment: 0.30 (0.20-0.50) of it") != std::string::npos);
  // The bytes at the own copy take 0.5, 1 and 0.25 ms: the larger roof is 0.5, 1.0, 0.25.
  CHECK(ceiling.find("at the buffers' copy: 0.50 (0.25-1.00)") != std::string::npos);
}

TEST_CASE("roofline: the timed steps run in segments, each followed by its roofs", "[engine][roofline]") {
  Model model = build_model(bench_bed_case(2000));
  Simulation sim(model, make_backend("cpu", -1, 1, KernelVariant{}.workgroup), KernelVariant{}, 50);
  sim.advance(50);
  sim.set_profiling(true);
  sim.take_profile();
  RooflineRun run = profile_against_roofs(sim, 103, 4);
  REQUIRE(run.segments.size() == 4);
  double contact_seconds = 0;
  for (const RoofSegment& s : run.segments) {
    CHECK(s.profile.steps >= 25);
    CHECK(s.roofs.own > 0);
    CHECK(s.roofs.dram > 0);
    CHECK(s.roofs.law > 0);  // free spheres in lanes
    contact_seconds += s.profile.kernels.at("contact_forces");
  }
  RunProfile total = run.total();
  CHECK(total.steps == 103);
  CHECK(sim.step() == 153);
  CHECK(total.kernels.at("contact_forces") == Approx(contact_seconds));
  CHECK(run.own_bytes == sim.backend().memory_bytes());
  TrafficCounts counts{2000, double(sim.contacts()), double(sim.contacts()), double(model.table_size) + 2};
  CHECK(row_of(format_roofline(run, sim.layout(), counts), "contact_forces").size() == 8);
  CHECK(!format_law_ceiling(run, sim.layout(), counts).empty());
  // Without segments: one part, no roofs, no ceiling.
  RooflineRun plain = profile_against_roofs(sim, 10, 0);
  REQUIRE(plain.segments.size() == 1);
  CHECK(plain.segments[0].profile.steps == 10);
  CHECK(plain.segments[0].roofs.own == 0);
  CHECK(format_law_ceiling(plain, sim.layout(), counts).empty());
}
