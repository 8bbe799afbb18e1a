// The angle of repose by draining (host/experiments/drain.h) on the shipped narrow box of 300
// spheres (a few CPU seconds): what stays behind stands as a slope falling towards the opening,
// frictionless spheres hold none, and the case keys are the experiment's own.
#include <catch2/catch.hpp>

#include "case/case_error.h"
#include "case/case_loader.h"
#include "experiments/drain.h"

using namespace repose;

namespace {

const std::string kBox = REPOSE_SOURCE_DIR "/cases/experiments/drain_box_spheres.toml";

std::string error_of(const std::vector<CaseOverride>& overrides) {
  try {
    load_case(kBox, overrides);
  } catch (const CaseError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("drain: the box empties through its opening and what stays slopes down towards it", "[experiments][drain]") {
  DrainResult r = run_drain(load_case(kBox));
  INFO("angle " << r.angle_deg << " deg, drained " << r.drained_fraction << ", left " << r.particles_left);
  // The opening (x 45-70 mm of a 70 mm box) faces the right slope; the back wall's face is none.
  CHECK(r.heap.right.valid);
  CHECK_FALSE(r.heap.left.valid);
  CHECK(r.angle_deg == r.heap.right.angle_deg);
  // What lay above the opening left, what leans on the back wall stayed: a slope from the wall's
  // top down to the opening's edge. With mu_s 0.5 and mu_r 0.1 it stands at 43.6 deg; the bounds
  // only say it is a granular slope, between a frictionless bed's none and a wall.
  CHECK(r.drained_fraction > 0.3);
  CHECK(r.drained_fraction < 0.95);
  CHECK(r.angle_deg > 20);
  CHECK(r.angle_deg < 60);
  // The fitted slope meets the floor at the opening's edge (x = 45 mm), within a diameter.
  double foot = (r.floor_z - r.heap.right.line.intercept) / r.heap.right.line.slope;
  CHECK(foot == Approx(0.045).margin(0.005));
}

TEST_CASE("drain: frictionless spheres hold no slope, the box empties", "[experiments][drain]") {
  // Without friction nothing resists sliding on the floor or over each other: the spheres run out
  // until only those stopped dead in a corner stay (2 % of 300: six spheres).
  std::vector<CaseOverride> frictionless;
  for (const char* pair : {"interaction.0.", "interaction.1."})
    for (const char* key : {"static_friction", "rolling_friction"}) frictionless.push_back({std::string(pair) + key, "0.0"});
  DrainResult r = run_drain(load_case(kBox, frictionless), {}, false);
  INFO(r.particles_left << " spheres left");
  CHECK(r.drained_fraction > 0.98);
}

TEST_CASE("drain: its keys are its own, the gate must exist and move", "[experiments][drain]") {
  CHECK_THAT(error_of({{"experiment.gate", "\"gat\""}}),
             Catch::Contains("experiment.gate") && Catch::Contains("no [[wall]] is named 'gat'") &&
                 Catch::Contains("did you mean 'gate'?"));
  CHECK_THAT(error_of({{"experiment.lift_wall", "\"gate\""}}),
             Catch::Contains("lift_wall") && Catch::Contains("[experiment] of type 'drain'"));
  CHECK_THAT(error_of({{"experiment.settle_energy", "-1"}}), Catch::Contains("experiment.settle_energy"));
  CaseSpec still = load_case(kBox, {{"wall.gate.motion.velocity", "[0.0, 0.0, 0.0]"}});
  CHECK_THROWS_WITH(run_drain(still), Catch::Contains("the gate 'gate' must move"));
}
