// A timed run names where its host time goes (RunProfile, format_host_times): its batches beyond
// their kernels (on a device: pipelines created, recording, the device's gaps between kernels,
// submit and wait) and the transfers around them; a checkpoint keeps those times.
#include <catch2/catch.hpp>

#include "engine/run_profile.h"
#include "engine_test_support.h"
#include "experiments/experiment_checkpoint.h"
#include "vk/context.h"
#include "vk/kernel_set.h"

using namespace repose;
using namespace repose::test;

namespace {

RunProfile timed_run(const std::string& backend, RunProfile* later = nullptr) {
  auto sim = simulate(seeded_cloud(200, 5, 2.3, 0.2), backend, 1, {}, 20);
  sim->set_profiling(true);
  sim->advance(100);  // five batches, each with its control words read back
  RunProfile first = sim->take_profile();
  if (later) {
    sim->advance(100);
    *later = sim->take_profile();
  }
  return first;
}

}  // namespace

TEST_CASE("a timed run names its host time: batches beyond their kernels and transfers", "[profile]") {
  for (const std::string backend : {"cpu", "vulkan"}) {
    INFO(backend);
    RunProfile later;
    RunProfile p = timed_run(backend, &later);
    REQUIRE(p.steps == 100);
    REQUIRE(!p.kernels.empty());
    CHECK(p.transfer_seconds > 0);  // a batch's control words come back after it
    CHECK(p.batch_seconds + p.transfer_seconds <= p.wall_seconds);
    // A batch waits for its kernels: on a device, their timestamps lie within its submit and wait.
    CHECK(p.batch_seconds >= p.kernel_seconds());
    if (backend == "cpu") {  // the host runs the kernels itself: nothing to record, no device
      CHECK(p.device.pipelines == 0);
      CHECK(p.device.recording == 0);
      CHECK(p.device.between_kernels == 0);
    } else {
      CHECK(p.device.recording > 0);
      CHECK(p.device.between_kernels > 0);  // a barrier after every kernel
      CHECK(p.device.total() <= p.batch_seconds - p.kernel_seconds());
      CHECK(later.device.pipelines == 0);  // created once: the next batches reuse them
      CHECK(later.device.recording > 0);
    }
    const std::string line = format_host_times(p);
    CHECK(line.find("ms per step: running the batches besides their kernels") != std::string::npos);
    CHECK(line.find(", transfers ") != std::string::npos);
    CHECK((line.find("recording the commands") != std::string::npos) == (backend == "vulkan"));
    CHECK((line.find("creating pipelines") != std::string::npos) == (p.device.pipelines > 0));
    CHECK(format_host_times(later).find("creating pipelines") == std::string::npos);
  }
}

TEST_CASE("an untimed profile has no host line; a checkpoint keeps the host times", "[profile]") {
  RunProfile untimed;
  untimed.steps = 10;
  untimed.wall_seconds = 1;
  CHECK(format_host_times(untimed).empty());

  RunProfile p = timed_run("cpu");
  p.device.pipelines = 0.5;  // as a device's would be
  p.device.recording = 0.25;
  p.device.between_kernels = 0.125;
  p.reorders = 2;
  p.reorder_seconds = 1.0;
  p.reorder_parts = {0.375, 0.25, 0.3125};
  RunProfile back = profile_from_json(profile_json(p));
  CHECK(back.reorder_parts.download == 0.375);
  CHECK(back.reorder_parts.order == 0.25);
  CHECK(back.reorder_parts.upload == 0.3125);
  CHECK(format_kernel_times(back).find("2 reorders on the host, 500.0 ms each (the state down 187.5, into its new slots "
                                       "125.0, up 156.2)") != std::string::npos);
  CHECK(back.batch_seconds == p.batch_seconds);
  CHECK(back.device.pipelines == 0.5);
  CHECK(back.device.recording == 0.25);
  CHECK(back.device.between_kernels == 0.125);
  CHECK(back.transfer_seconds == p.transfer_seconds);

  OrderedJson older = profile_json(p);  // a checkpoint written before these were timed
  for (const char* key : {"batch_seconds", "pipeline_seconds", "recording_seconds", "between_kernels_seconds",
                          "transfer_seconds", "reorder_download_seconds", "reorder_order_seconds", "reorder_upload_seconds"})
    older.erase(key);
  RunProfile read = profile_from_json(older);
  CHECK(read.reorder_parts.download + read.reorder_parts.order + read.reorder_parts.upload == 0);
  CHECK(format_kernel_times(read).find("500.0 ms each") != std::string::npos);
  CHECK(format_kernel_times(read).find("the state down") == std::string::npos);  // not timed: not named
  CHECK(read.batch_seconds == 0);
  CHECK(read.transfer_seconds == 0);
  CHECK(format_host_times(read).find("transfers 0.000") != std::string::npos);
}

TEST_CASE("the device's pipelines are created once per process: a second simulation reuses them", "[profile]") {
  vk::PipelineLibrary& library = vk::Context::open()->pipelines();
  for (int run = 0; run < 2; ++run) {
    INFO("simulation " << run + 1);
    auto sim = simulate(seeded_cloud(200, 5, 2.3, 0.2), "vulkan", 1, {}, 20);
    const size_t after_setup = library.size();
    sim->set_profiling(true);
    sim->advance(100);
    RunProfile p = sim->take_profile();
    CHECK(p.kernel_seconds() > 0);
    // The batches' own first uses are timed (the setup's are not), and only they.
    CHECK((p.device.pipelines > 0) == (library.size() > after_setup));
    if (run == 1) CHECK(p.device.pipelines == 0);  // the first simulation made every one it needs
  }
}

// Under ctest each test case is a process of its own, so the device's library starts empty here:
// a pipeline that Simulation::dispatches_of_run() missed would be made in a batch and fail this.
TEST_CASE("a simulation's setup makes every pipeline its batches use, several at once", "[profile]") {
  vk::PipelineLibrary& library = vk::Context::open()->pipelines();
  const std::vector<std::pair<const char*, CaseSpec>> cases = {
      {"spheres by two walls", seeded_cloud(200, 5, 2.3, 0.2)},
      {"clumps", clump_pile()},
      {"clumps, symplectic Euler", wide_skin_pile(Integrator::SymplecticEuler)}};
  for (const auto& [name, spec] : cases) {
    INFO(name);
    auto sim = simulate(spec, "vulkan", 1, {}, 20);
    const size_t made = library.size();
    CHECK(made > 0);
    sim->sum_wall_forces();
    sim->advance(60);
    sim->wall_forces();
    CHECK(library.size() == made);
  }
}
