// Denormals: a GPU without shaderDenormPreserveFloat32 (the NVIDIA H200) flushes them to zero,
// lavapipe and the CPU twin keep them. Determinism across backends then needs that no denormal
// reaches the state. The CPU twin run with the processor flushing them (MXCSR FTZ and DAZ) must
// give the bytes of a run that keeps them, on each kind of case the tests already compare.
#include <catch2/catch.hpp>

#include "case/case_loader.h"
#include "engine_test_support.h"

using namespace repose;
using namespace repose::test;

namespace {

void check_flushing_changes_nothing(const CaseSpec& spec, uint64_t steps, const char* what) {
  auto kept = simulate(spec, "cpu", 2, {}, 25);
  kept->advance(steps);
  std::string which;
  bool same = same_state(kept->state(), simulate_flushing_denormals(spec, steps)->state(), &which);
  INFO(what << ": differs in " << which);
  CHECK(same);
}

// Spheres rolling on a plate with a little spin about the vertical, under EDEM's constant rolling
// torque against their own spin (mu_r 0.3, the large heap's rubber mat): once a roll has stopped,
// the torque's vertical share mu_r R |Fn| w_z / |w| shrinks w_z step after step (the large heap's
// grains resting on the mat did this on an H200, 2026-11-27).
CaseSpec rolling_on_plate() {
  CaseBuilder b;
  int grain = b.material(850, 1.09e6, 0.32);
  int mat = b.material(1200, 1e7, 0.45);
  b.interaction(grain, grain, 0.42, 0.457, 0.039);
  b.interaction(grain, mat, 0.2, 0.9, 0.3);
  b.spec.gravity = {0, 0, -9.81};
  b.spec.time.rayleigh_fraction = 0.2;
  for (int k = 0; k < 8; ++k)
    b.sphere({0.03 * k, 0, 0.00499}, 0.005, grain, {0.02 * k, 0, 0}, {0, 4.0 * k - 10.0, 0.3 + 0.1 * k});
  b.plane({0, 0, 0}, {0, 0, 1}, mat);
  return b.spec;
}

}  // namespace

TEST_CASE("denormals flushed or kept: the same bytes for spheres rolling to rest with a spin about the vertical",
          "[engine][bitexact]") {
  check_flushing_changes_nothing(rolling_on_plate(), 6000, "spheres rolling on a plate");
}

TEST_CASE("denormals flushed or kept: the same bytes for spheres, walls, clumps and rolling springs", "[engine][bitexact]") {
  check_flushing_changes_nothing(seeded_cloud(300, 7, 2.3, 0.2), 1500, "a cloud with walls");
  check_flushing_changes_nothing(clump_pile(), 1500, "a clump pile");
  check_flushing_changes_nothing(epsd_clump_pairs(), 1500, "clumps with EPSD rolling springs");
  check_flushing_changes_nothing(wide_skin_pile(), 1500, "a pile with a wide skin");
}

TEST_CASE("denormals flushed or kept: the same bytes for the shipped settling box and cabbage settle", "[engine][bitexact]") {
  for (const char* name : {"settle_box.toml", "cabbage_settle.toml"}) {
    CaseSpec spec = load_case(std::string(REPOSE_SOURCE_DIR) + "/cases/" + name);
    check_flushing_changes_nothing(spec, 600, name);
  }
}
