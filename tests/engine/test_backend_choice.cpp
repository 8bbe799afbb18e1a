// The default backend: a hardware GPU when there is one, else the cpu backend (lavapipe, Vulkan
// on the CPU, stays available by name and is what the tests run on).
#include <catch2/catch.hpp>

#include "../cli_support.h"
#include "engine/backend_factory.h"

using namespace repose;

namespace {

vk::DeviceInfo device(uint32_t index, const char* name, const char* type) {
  vk::DeviceInfo d;
  d.index = index;
  d.name = name;
  d.type = type;
  return d;
}

}  // namespace

TEST_CASE("the default backend is a hardware GPU when there is one, else the cpu backend", "[engine]") {
  auto lavapipe = device(0, "llvmpipe", "cpu");
  BackendChoice only_cpu = choose_backend({lavapipe});
  CHECK(only_cpu.backend == "cpu");
  CHECK(only_cpu.reason.find("--backend vulkan --device 0") != std::string::npos);
  CHECK(choose_backend({}).backend == "cpu");

  BackendChoice discrete = choose_backend({lavapipe, device(1, "iGPU", "integrated-gpu"), device(2, "dGPU", "discrete-gpu")});
  CHECK(discrete.backend == "vulkan");
  CHECK(discrete.device == 2);
  BackendChoice integrated = choose_backend({lavapipe, device(1, "iGPU", "integrated-gpu")});
  CHECK(integrated.backend == "vulkan");
  CHECK(integrated.device == 1);

  // Named backends stay as named; a named device means Vulkan.
  CHECK(resolve_backend("vulkan", -1).backend == "vulkan");
  CHECK(resolve_backend("cpu", -1).backend == "cpu");
  CHECK(resolve_backend("auto", 0).backend == "vulkan");
  CHECK(resolve_backend("auto", 0).device == 0);
}

TEST_CASE("repose devices says which backend runs by default and why", "[engine][vulkan]") {
  auto r = repose::test::run_repose("devices");
  REQUIRE(r.status == 0);
  // The tests see lavapipe only (VK_DRIVER_FILES), so the default is the cpu backend.
  CHECK(r.output.find("default backend: cpu") != std::string::npos);
  CHECK(r.output.find("no hardware GPU") != std::string::npos);
}
