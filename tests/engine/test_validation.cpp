// One leg on lavapipe with the Khronos validation layer: any message it sends fails the test.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>

#include "case/case_loader.h"
#include "engine/vulkan_backend.h"
#include "engine_test_support.h"
#include "tests/cli_support.h"

using namespace repose;

TEST_CASE("Vulkan backend under the validation layer sends no message", "[engine][vulkan][validation]") {
  ::setenv("REPOSE_VALIDATION", "1", 1);
  CaseSpec spec = load_case(std::string(REPOSE_SOURCE_DIR) + "/cases/settle_box.toml");
  auto backend = std::make_unique<VulkanBackend>(-1, 64u);
  VulkanBackend* vk = backend.get();
  REQUIRE(vk->context().validation_enabled());
  {
    Simulation sim(build_model(spec), std::move(backend), {}, 20);
    sim.advance(40);
    sim.wall_forces();
    CHECK(sim.contacts() > 0);
    CHECK(vk->validation_messages() == 0);
  }
  ::unsetenv("REPOSE_VALIDATION");
}

TEST_CASE("repose devices lists lavapipe", "[engine][vulkan]") {
  auto r = repose::test::run_repose("devices");
  REQUIRE(r.status == 0);
  const std::string& text = r.output;
  CHECK(text.find("llvmpipe") != std::string::npos);
}
