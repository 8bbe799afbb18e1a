// Restart: a run of N steps written to a state file and continued for M steps gives the bytes of
// a run of N + M steps, with walls that move, clump bodies, EPSD rolling springs, the symplectic
// Euler integrator, a restart step that is no multiple of the batch, and across backends.
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "engine_test_support.h"
#include "io/state_file.h"

using namespace repose;
using namespace repose::test;

namespace {

// Per process: ctest runs the test cases of this file at the same time.
std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("repose_test_" + std::to_string(::getpid()) + "_" + name)).string();
}

// The state after n + m steps in one go and after n steps, a state file, and m more (on
// `backend_after`, with batches of `batch_after`): every byte of the file must agree.
void check_restart(const CaseSpec& spec, uint64_t n, uint64_t m, const std::string& backend_after = "cpu",
                   uint32_t batch_after = 200) {
  auto whole = simulate(spec, "cpu", 2);
  whole->advance(n + m);
  std::string full = temp_path("restart_full.state"), part = temp_path("restart_part.state"),
              resumed = temp_path("restart_resumed.state");
  write_state_file(full, whole->state(), whole->step(), whole->time());

  auto first = simulate(spec, "cpu", 1, {}, 64);
  first->advance(n);
  write_state_file(part, first->state(), first->step(), first->time());
  StateFileInfo info;
  HostState state = read_state_file(part, info);
  REQUIRE(info.restartable());
  REQUIRE(info.step == n);
  auto second = simulate(spec, backend_after, 1, {}, batch_after);
  second->restore(state, info.step);
  second->advance(m);
  write_state_file(resumed, second->state(), second->step(), second->time());

  uint64_t step = 0;
  HostState a = read_state_file(full, &step), b = read_state_file(resumed);
  std::string which;
  CHECK(same_state(a, b, &which));
  INFO("first differing array: " << which);
  CHECK(which.empty());
  CHECK(second->rebuilds() == whole->rebuilds());
  std::ifstream fa(full, std::ios::binary), fb(resumed, std::ios::binary);
  std::string ba((std::istreambuf_iterator<char>(fa)), {}), bb((std::istreambuf_iterator<char>(fb)), {});
  CHECK(ba == bb);
  for (const auto& p : {full, part, resumed}) std::remove(p.c_str());
}

}  // namespace

TEST_CASE("restart: a cloud with walls continues to the bytes of an uninterrupted run", "[engine][restart]") {
  CaseSpec spec = seeded_cloud(300, 7, 2.3, 0.2);
  check_restart(spec, 137, 263);
}

TEST_CASE("restart: a moving wall, symplectic Euler, lavapipe continuing the CPU twin's state", "[engine][restart]") {
  CaseSpec spec = seeded_cloud(200, 3, 2.3, 0.2);
  spec.integrator = Integrator::SymplecticEuler;
  spec.walls[1].motion.velocity = {0.2, 0, 0};
  spec.walls[1].motion.stop_time = 1.0;
  check_restart(spec, 150, 150, "vulkan", 37);
}

TEST_CASE("restart: clumps with EPSD rolling springs", "[engine][restart]") {
  check_restart(epsd_clump_pairs(), 211, 300);
}

TEST_CASE("restart: a state that does not fit the case is refused by what differs", "[engine][restart]") {
  CaseSpec spec = seeded_cloud(50, 1, 2.3, 0.2);
  auto sim = simulate(spec);
  sim->advance(10);
  HostState s = sim->state();
  auto other = simulate(seeded_cloud(60, 1, 2.3, 0.2));
  CHECK_THROWS_WITH(other->restore(s, 10), Catch::Matchers::Contains("50 particles in the state, 60 in the case"));
}
