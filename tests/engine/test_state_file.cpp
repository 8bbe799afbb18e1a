// The state file (docs/state-format.md): a run's state written and read back is the same bytes,
// rolling springs and bodies included; a version 2 file (144-byte bodies, no rolling springs)
// still reads; a file that is not one is refused by name.
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "engine_test_support.h"
#include "io/state_file.h"

using namespace repose;
using namespace repose::test;

namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("repose_test_" + name)).string();
}

}  // namespace

TEST_CASE("state file round trip keeps every byte, with bodies and rolling springs", "[engine][io]") {
  auto sim = simulate(epsd_clump_pairs(), "cpu", 1, {}, 50);
  sim->advance(300);
  REQUIRE(!sim->state().rolling_spring.empty());
  std::string path = temp_path("roundtrip.state");
  write_state_file(path, sim->state(), sim->step(), sim->time());
  uint64_t step = 0;
  double time = 0;
  HostState back = read_state_file(path, &step, &time);
  std::remove(path.c_str());
  CHECK(step == sim->step());
  CHECK(time == sim->time());
  for (auto [a, c] : {std::pair{&back.pos, &sim->state().pos}, {&back.history, &sim->state().history},
                      {&back.rolling_spring, &sim->state().rolling_spring}})
    CHECK(same_bytes(*a, *c));
  CHECK(same_bytes(back.bodies, sim->state().bodies));
}

TEST_CASE("a version 2 state file (144-byte bodies) still reads", "[engine][io]") {
  std::string path = temp_path("v2.state");
  {
    std::ofstream out(path, std::ios::binary);
    out.write(kStateMagicV2, 8);
    uint32_t n = 1, c = 0, bodies = 1;
    uint64_t step = 7;
    double time = 0.5;
    out.write(reinterpret_cast<const char*>(&n), 4);
    out.write(reinterpret_cast<const char*>(&c), 4);
    out.write(reinterpret_cast<const char*>(&bodies), 4);
    out.write(reinterpret_cast<const char*>(&step), 8);
    out.write(reinterpret_cast<const char*>(&time), 8);
    gpu::vec4 p(1, 2, 3, 0.5f);
    for (int k = 0; k < 5; ++k) out.write(reinterpret_cast<const char*>(&p), sizeof p);  // pos .. torque
    uint32_t rows[2] = {0, 0};
    out.write(reinterpret_cast<const char*>(rows), sizeof rows);
    gpu::Body body{};
    body.pos = gpu::vec4(4, 5, 6, 2);
    body.spheres = gpu::uvec4(0, 1, 0, 0);
    out.write(reinterpret_cast<const char*>(&body), 144);
  }
  uint64_t step = 0;
  HostState s = read_state_file(path, &step);
  std::remove(path.c_str());
  CHECK(step == 7);
  REQUIRE(s.bodies.size() == 1);
  CHECK(s.bodies[0].pos.z == 6.0f);
  CHECK(s.bodies[0].spheres.y == 1u);
  CHECK(s.bodies[0].drag.x == 0.0f);
  CHECK(s.rolling_spring.empty());
}

TEST_CASE("a file that is not a state file is refused by name", "[engine][io]") {
  std::string path = temp_path("not.state");
  std::ofstream(path) << "hello";
  CHECK_THROWS_WITH(read_state_file(path), Catch::Matchers::Contains(path) && Catch::Matchers::Contains("not a Repose state file"));
  std::remove(path.c_str());
}
