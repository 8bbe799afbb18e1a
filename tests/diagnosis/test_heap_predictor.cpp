// The heap side of the diagnosis (angle-of-repose rig, measures repose_angle and bed_height) on
// cases/diagnosis/slot_heap.toml: replicates refill the heap from seed + r, the same replicate
// gives the same bytes, the bed height is a real packing, and size_spread keeps the mean radius.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "case/case_loader.h"
#include "case/particle_factory.h"
#include "case/case_error.h"
#include "diagnosis/bond_number.h"
#include "diagnosis/predictor.h"
#include "experiments/heap_fill.h"
#include "experiments/repose.h"

using namespace repose;
namespace fs = std::filesystem;

namespace {

std::string slot_heap() { return std::string(REPOSE_SOURCE_DIR) + "/cases/diagnosis/slot_heap.toml"; }

// A one-condition heap dataset next to a copy of the case (the values only need to parse).
Observations heap_observations() {
  fs::path dir = fs::temp_directory_path() / "repose_heap_predictor";
  fs::create_directories(dir);
  fs::copy_file(slot_heap(), dir / "slot_heap.toml", fs::copy_options::overwrite_existing);
  std::ofstream(dir / "data.csv") << "case,measure,value,replicate\n"
                                     "slot_heap.toml,repose_angle,24,1\nslot_heap.toml,repose_angle,26,2\n"
                                     "slot_heap.toml,bed_height,0.08,1\nslot_heap.toml,bed_height,0.081,2\n";
  return group_observations(read_measured_data((dir / "data.csv").string()));
}

}  // namespace

TEST_CASE("heap predictor: replicates refill from seed + r, a replicate repeats to the byte, the bed packs",
          "[diagnosis][heap]") {
  Observations obs = heap_observations();
  Predictor predictor(obs, {}, true, 2, 2);
  REQUIRE(predictor.experiment() == "repose");
  CHECK(predictor.stochastic(nullptr, {0.5}));
  auto params = predictor.parameters(nullptr);
  REQUIRE(params.size() == 1);
  CHECK(params[0].name == "static_friction");
  Outcome a = predictor.simulate(0, nullptr, {0.5}, 0);
  Outcome b = predictor.simulate(0, nullptr, {0.5}, 1);
  CHECK(a.values.at("repose_angle") != b.values.at("repose_angle"));  // another fill, another heap
  // The same replicate again, bypassing the cache through a second predictor: the same bytes.
  Predictor again(obs, {}, true, 1, 2);
  Outcome a2 = again.simulate(0, nullptr, {0.5}, 0);
  CHECK(a2.values.at("repose_angle") == a.values.at("repose_angle"));
  CHECK(a2.values.at("bed_height") == a.values.at("bed_height"));
  // The bed before the lift: 200 spheres of 5 mm over the gate's 80 x 30 mm floor. Random
  // packings lie between ~0.55 (loose) and 0.64 (dense); three diameters between walls loosen
  // them further, so the implied packing fraction must lie in [0.45, 0.65].
  for (const Outcome* o : {&a, &b}) {
    double solid = 200 * 4.0 / 3.0 * 3.14159265358979 * 0.005 * 0.005 * 0.005;
    double phi = solid / (0.08 * 0.03 * o->values.at("bed_height"));
    INFO("bed height " << o->values.at("bed_height") << " m, packing fraction " << phi);
    CHECK(phi > 0.45);
    CHECK(phi < 0.65);
    CHECK(o->values.at("repose_angle") > 10);
    CHECK(o->values.at("repose_angle") < 40);
  }
}

TEST_CASE("size_spread: fill radii uniform in [r(1-s), r(1+s)] about the case's mean radius", "[diagnosis][heap]") {
  CaseSpec spec = load_case(slot_heap());
  const ModelExtension* spread = find_extension("size_spread");
  REQUIRE(spread);
  REQUIRE(spread->apply);
  spread->apply(spec, {0.3});
  spec.spheres.clear();
  expand_particles(spec);
  REQUIRE(spec.spheres.size() == 200);
  double lo = 1, hi = 0, mean = 0;
  for (const auto& s : spec.spheres) {
    lo = std::min(lo, s.radius);
    hi = std::max(hi, s.radius);
    mean += s.radius / 200;
  }
  CHECK(lo >= 0.0035);
  CHECK(hi <= 0.0065);
  CHECK(hi - lo > 0.0025);  // 200 uniform draws cover > 80 % of the 3 mm range
  // Mean of 200 uniform draws: standard error 0.0015 / sqrt(3 * 200) = 6e-5 m; 4 of them.
  CHECK(mean == Approx(0.005).margin(2.5e-4));
}

TEST_CASE("rolling_epsd switches a case to EDEM type C with the fitted damping and spinning friction",
          "[diagnosis][heap]") {
  CaseSpec spec = load_case(slot_heap());
  CHECK(spec.contact.rolling == RollingModel::ConstantTorque);
  find_extension("rolling_epsd")->apply(spec, {0.6});
  CHECK(spec.contact.rolling == RollingModel::ElasticPlastic);
  CHECK(spec.contact.rolling_damping == 0.6);
  // Twisting resistance equal to each pair's rolling friction (grain 0.1, wall 0.15).
  REQUIRE(spec.interactions.size() == 2);
  for (const auto& in : spec.interactions) CHECK(in.spinning_friction == in.rolling_friction);
  CHECK(spec.interactions[1].spinning_friction == 0.15);
}

TEST_CASE("the bed alone (no lift) measures the bed height run_repose measures, to the byte", "[diagnosis][heap]") {
  CaseSpec spec = load_case(slot_heap(), {{"fill.0.count", "120"}});
  spec.spheres.clear();
  expand_particles(spec);
  double bed = measure_bed_height(spec);
  ReposeResult heap = run_repose(spec, {}, true);
  CHECK(bed == heap.bed_height);
  CHECK(bed > 0.03);  // 120 grains of 10 mm over 80 x 30 mm: ~5 cm at a packing fraction of 0.55
}
TEST_CASE("a size spread too tight for the fill box is placed largest first, never lost", "[diagnosis][heap]") {
  // The failure: 250 grains with a spread of 0.4 (radii 3-7 mm) in the slot's 80 x 30 x
  // 300 mm box: random sequential addition leaves some without room.
  // 300 mm box: random sequential addition leaves some without room for some fill seeds.
  CaseSpec spec = load_case(slot_heap(), {{"fill.0.count", "250"}});
  find_extension("size_spread")->apply(spec, {0.4});
  spec.spheres.clear();
  bool plain_fails = false;
  for (uint64_t seed = 1; seed <= 60 && !plain_fails; ++seed) {
    spec.fills[0].seed = seed;
    CaseSpec plain = spec;
    try {
      expand_particles(plain);
    } catch (const CaseError& e) {
      CHECK_THAT(e.what(), Catch::Contains("of the 250 spheres (count) fit without overlap"));
      plain_fails = true;
    }
  }
  REQUIRE(plain_fails);
  INFO("fill seed " << spec.fills[0].seed);
  HeapFill how = fill_heap(spec);
  CHECK(how.fallback);
  CHECK(how.raised == 0);  // largest first, all 250 fit the case's own box (measured: the top at 0.2999 m)
  REQUIRE(spec.spheres.size() == 250);
  check_no_overlaps(spec.spheres);  // throws on any overlap
  // Inside the slot's walls: x in [0, 0.08] (behind the gate), y in [0, 0.03], above the floor.
  const FillSpec& f = spec.fills[0];
  for (const auto& s : spec.spheres) {
    CHECK(s.position[0] - s.radius >= 0.0);
    CHECK(s.position[0] + s.radius <= 0.08);
    CHECK(s.position[1] - s.radius >= 0.0);
    CHECK(s.position[1] + s.radius <= 0.03);
    CHECK(s.position[2] - s.radius >= 0.0);
    CHECK(s.position[2] + s.radius <= f.box_max[2] * (1 + how.raised) + 1e-12);
  }
}

TEST_CASE("a fill that fits keeps the case's own bytes, one that never fits is refused with why",
          "[diagnosis][heap]") {
  CaseSpec spec = load_case(slot_heap());
  spec.spheres.clear();
  CaseSpec plain = spec;
  expand_particles(plain);
  HeapFill how = fill_heap(spec);
  CHECK_FALSE(how.fallback);
  REQUIRE(spec.spheres.size() == plain.spheres.size());
  for (size_t k = 0; k < spec.spheres.size(); ++k) {
    CHECK(spec.spheres[k].position == plain.spheres[k].position);
    CHECK(spec.spheres[k].radius == plain.spheres[k].radius);
  }
  CaseSpec crowded = load_case(slot_heap());
  crowded.spheres.clear();
  crowded.fills[0].count = 3000;  // more grain volume than twice the box holds
  CHECK_THROWS_WITH(fill_heap(crowded), Catch::Contains("do not fit the fill box even placed largest first"));
}

TEST_CASE("cohesion in a heap attracts grain to grain and keeps the case's friction convention",
          "[diagnosis][heap]") {
  CaseSpec spec = load_case(slot_heap());
  CohesionFriction convention = spec.contact.cohesion_friction;
  find_extension("cohesion")->apply(spec, {5000.0});
  REQUIRE(spec.interactions.size() == 2);
  CHECK(spec.interactions[0].cohesion_energy_density == 5000.0);  // grain-grain
  CHECK(spec.interactions[1].cohesion_energy_density == 0.0);     // grain-wall: dry walls
  CHECK(spec.contact.cohesion_friction == convention);
}

TEST_CASE("granular Bond number of the slot heap's grains: pull-off force over weight", "[diagnosis][heap]") {
  // 10 mm grains, 1000 kg/m^3 (weight 5.14e-3 N), G 5e4 Pa, nu 0.3: E* = 7.14e4 Pa, R* = 2.5 mm.
  // At k = 8000 J/m^3: k pi R* = 62.8 N/m, 4/3 E* sqrt(R*) = 4762 N/m^1.5, pull-off
  // 4/27 62.8^3 / 4762^2 = 1.62e-3 N: Bo = 0.315.
  CaseSpec spec = load_case(slot_heap());
  CHECK(heap_bond_number(spec, 8000) == Approx(0.315).epsilon(0.01));
  CHECK(heap_cohesion_for_bond_number(spec, heap_bond_number(spec, 8000)) == Approx(8000));
  // The heap's search range: Bond numbers 1e-3 to 3.
  Observations obs = heap_observations();
  Predictor predictor(obs, {}, false, 1, 2);
  auto params = predictor.parameters(find_extension("cohesion"));
  REQUIRE(params.size() == 1);
  CHECK(heap_bond_number(spec, params[0].lo) == Approx(1e-3));
  CHECK(heap_bond_number(spec, params[0].hi) == Approx(3));
}

