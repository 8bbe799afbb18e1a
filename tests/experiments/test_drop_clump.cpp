// The drop experiment with clump bodies: a vertical dumbbell rebounds like a sphere, and the
// cabbage clump lands at a random orientation per seed (replicates), deterministically.
#include <catch2/catch.hpp>

#include "case/case_loader.h"
#include "experiments/drop.h"

using namespace repose;

namespace {

CaseSpec drop_case(bool dumbbell) {
  std::string text =
      "[simulation]\nend_time = 1\ndt = 2e-5\ngravity = [0, 0, -9.81]\n"
      "[experiment]\ntype = \"drop\"\ndrop_height = 0.3\n"
      "[[material]]\nname = \"g\"\ndensity = 850\nshear_modulus = 1.09e6\npoisson = 0.32\n"
      "[[material]]\nname = \"steel\"\npreset = \"q235_steel\"\n"
      "[[interaction]]\nmaterials = [\"g\", \"steel\"]\nrestitution = 0.43\nstatic_friction = 0.5\n"
      "rolling_friction = 0\n"
      "[[wall]]\ntype = \"plane\"\nmaterial = \"steel\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\n";
  if (dumbbell)
    text += "[[template]]\nname = \"bell\"\nfile = \"bell.csv\"\n"
            "[[clump]]\ntemplate = \"bell\"\nmaterial = \"g\"\nposition = [0, 0, 1]\n";
  else
    text += "[[sphere]]\nmaterial = \"g\"\nradius = 0.04\nposition = [0, 0, 1]\n";
  return load_case_from_string(text, std::string(REPOSE_SOURCE_DIR) + "/tests/experiments/data/drop.toml");
}

}  // namespace

TEST_CASE("a vertical dumbbell clump rebounds like its sphere", "[experiments][drop][clump]") {
  DropResult sphere = run_drop(drop_case(false));
  DropOptions upright;
  upright.random_orientation = false;
  DropResult bell = run_drop(drop_case(true), upright);
  INFO("sphere e = " << sphere.restitution << ", dumbbell e = " << bell.restitution);
  // Same pair restitution, contact through the centre of mass; gravity during the softer
  // contact of the heavier body shifts sqrt(h/H) a little (ENGINEERING.md): 1 %.
  CHECK(bell.restitution == Approx(sphere.restitution).epsilon(0.01));
  CHECK(bell.trajectory.front().second == Approx(0.3).margin(1e-6));
}

TEST_CASE("cabbage clump drops: one random orientation per seed, reproducible", "[experiments][drop][clump]") {
  const std::string path = std::string(REPOSE_SOURCE_DIR) + "/cases/drop_cabbage.toml";
  std::vector<double> e;
  const CaseOverride pair{"interaction.cabbage/q235_steel.restitution", "0.9"};
  for (int seed : {1, 2, 3}) {
    CaseSpec spec = load_case(path, {{"simulation.seed", std::to_string(seed)}, pair});
    DropResult r = run_drop(spec);
    e.push_back(r.restitution);
    CHECK(r.trajectory.front().second == Approx(0.5).margin(1e-6));
    // A body landing off its centre of mass, on several veins at once, keeps less of its
    // bounce than one sphere would (spin, parallel dashpots): below the pair's 0.9, but a
    // clear rebound (0.66-0.75 measured).
    CHECK(r.restitution > 0.5);
    CHECK(r.restitution < 0.9);
  }
  CHECK(e[0] != e[1]);
  CHECK(e[1] != e[2]);
  CaseSpec again = load_case(path, {{"simulation.seed", "2"}, pair});
  CHECK(run_drop(again).restitution == e[1]);  // same seed, same bytes
}
