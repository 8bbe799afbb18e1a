// The heap side of the diagnosis (angle-of-repose rig, measures repose_angle and bed_height) on
// cases/diagnosis/slot_heap.toml: replicates refill the heap from seed + r, the same replicate
// gives the same bytes, the bed height is a real packing, and size_spread keeps the mean radius.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "case/case_loader.h"
#include "case/particle_factory.h"
#include "experiments/repose.h"
#include "diagnosis/predictor.h"
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
