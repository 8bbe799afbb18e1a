// The state comes back from the device only when something reads it (Simulation::state): runs
// read after every batch, read by rows alone after every batch (the escape check of `repose run`,
// an experiment's largest kinetic energy) or read only at the end give the same bytes on both
// backends, through overflow retries (which upload the last state read and run the batches since
// again) and reorders; a run nobody reads downloads no state at all (Backend::state_downloads).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "engine/bench_bed.h"
#include "engine/kinetic_energy.h"
#include "engine_test_support.h"
#include "io/state_file.h"

using namespace repose;
using namespace repose::test;

namespace {

std::string state_file_bytes(const Simulation& sim) {
  std::string path = (std::filesystem::temp_directory_path() /
                      ("repose_test_" + std::to_string(::getpid()) + "_lazy.state")).string();
  write_state_file(path, sim.state(), sim.step(), sim.time());
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  std::remove(path.c_str());
  return bytes;
}

// True when `any` (one row of every particle in the device's slots) holds, slot for slot, the
// bytes of the state's row (by global id) of the particle stored there.
bool same_row_in_slots(const std::vector<gpu::vec4>& any, const std::vector<gpu::vec4>& by_id,
                       const ParticleOrder& order) {
  if (any.size() != by_id.size()) return false;
  for (uint32_t slot = 0; slot < any.size(); ++slot)
    if (std::memcmp(&any[slot], &by_id[order.id_of[slot]], sizeof(gpu::vec4)) != 0) return false;
  return true;
}

// The rows a check reads alone (the escape check's positions, the largest kinetic energy's
// velocities and spins), each in the device's slots and as the state has them.
constexpr std::vector<gpu::vec4> HostState::*kRowsAlone[] = {&HostState::pos, &HostState::vel, &HostState::omega};

bool same_rows_in_slots(const std::vector<std::vector<gpu::vec4>>& any, const Simulation& sim) {
  for (size_t r = 0; r < any.size(); ++r)
    if (!same_row_in_slots(any[r], sim.state().*kRowsAlone[r], sim.particle_order())) return false;
  return true;
}

std::vector<std::vector<gpu::vec4>> rows_alone(const Simulation& sim) {
  std::vector<std::vector<gpu::vec4>> rows;
  for (auto row : kRowsAlone) rows.push_back(sim.rows_in_any_order(row));
  return rows;
}

enum class Reading { EveryBatch, RowsEveryBatch, AtTheEnd };

const char* name_of(Reading r) {
  return r == Reading::EveryBatch ? "state read after every batch"
         : r == Reading::RowsEveryBatch ? "rows read alone after every batch" : "read at the end";
}

}  // namespace

TEST_CASE("lazy download: runs read after every batch, by rows alone or only at the end give the same bytes",
          "[engine][order][lazy]") {
  // The pile's list of 64 entries overflows in the constructor and, grown, again near step 1000
  // (wide_skin_pile): a run nobody read since step 0 redoes that batch by running its 19 batches
  // again from the constructor's state.
  CaseSpec spec = wide_skin_pile();
  const uint32_t n = build_model(spec).n_particles;
  const uint64_t steps = 1100, batch = 50;
  auto start = [&](const std::string& backend, unsigned threads, const char* variant, uint32_t capacity) {
    KernelVariant v = KernelVariant::parse(variant);
    return std::make_unique<Simulation>(build_model(spec), make_backend(backend, -1, threads, v.workgroup), v,
                                        uint32_t(batch), capacity);
  };
  auto reference = start("cpu", 1, "reorder=0", 20 * n);
  reference->advance(steps);
  REQUIRE(reference->retries() == 0);
  const std::string reference_file = state_file_bytes(*reference);

  for (const char* backend : {"cpu", "vulkan"})
    for (const char* variant : {"reorder=0", "reorder=1"})
      for (Reading reading : {Reading::EveryBatch, Reading::RowsEveryBatch, Reading::AtTheEnd}) {
        INFO(backend << ", " << variant << ", " << name_of(reading));
        auto sim = start(backend, 2, variant, 64);
        uint64_t downloads_before = sim->backend().state_downloads();
        size_t batches = 0, rows_as_downloaded = 0;
        sim->advance(steps, [&](const Simulation& s) {
          ++batches;
          if (reading == Reading::AtTheEnd) return;
          auto any = rows_alone(s);
          double largest = largest_kinetic_energy(s);  // the bodies' rows, in the device's order
          if (reading == Reading::EveryBatch)  // and as the whole state has them, by global id
            rows_as_downloaded += same_rows_in_slots(any, s) && largest_kinetic_energy(s) == largest;
        });
        uint64_t downloads = sim->backend().state_downloads() - downloads_before;
        CHECK(sim->retries() > 0);
        CHECK(batches == steps / batch);
        if (reading == Reading::EveryBatch) {
          CHECK(rows_as_downloaded == batches);  // rows alone are the full download's
          CHECK(downloads == batches);                // one per batch: neither retries nor reorders add any
        } else if (std::string(variant) == "reorder=0") {
          CHECK(downloads == 0);  // the overflow near step 1000 ran its unread batches again
        } else {
          CHECK(downloads > 0);  // every reorder reads the state
        }
        // The last rows read alone, then the whole state: the same bytes, slot for slot.
        if (reading != Reading::EveryBatch) {
          auto any = rows_alone(*sim);
          CHECK(sim->backend().state_downloads() - downloads_before == downloads);
          CHECK(same_rows_in_slots(any, *sim));
        }
        std::string which;
        bool same = same_state(reference->state(), sim->state(), &which);
        INFO("first difference in " << which);
        CHECK(same);
        CHECK(same_bytes(reference->state().control, sim->state().control));
        CHECK(state_file_bytes(*sim) == reference_file);
        CHECK(same_bytes(reference->contact_forces(), sim->contact_forces()));
      }
}

TEST_CASE("lazy download: a bench-like run nobody reads downloads no state; a reading downloads it once",
          "[engine][lazy]") {
  // The bench's bed and its 50-step batches, with the default variant (cell order renewed every
  // 20 rebuilds: fewer happen here, so no reorder reads the state).
  Model model = build_model(bench_bed_case(2000));
  for (const char* backend : {"cpu", "vulkan"}) {
    INFO(backend);
    Simulation sim(model, make_backend(backend, -1, 1, KernelVariant{}.workgroup), KernelVariant{}, 50);
    const Backend& device = sim.backend();
    uint64_t at_start = device.state_downloads();
    sim.advance(300, [](const Simulation& s) { CHECK(s.contacts() > 0); });
    REQUIRE(sim.rebuilds() < 20);
    CHECK(device.state_downloads() == at_start);
    auto any = rows_alone(sim);  // rows alone: no state
    // The largest kinetic energy of all the spheres and of those left of the median.
    std::vector<float> xs;
    for (const auto& p : any[0]) xs.push_back(p.x);
    std::nth_element(xs.begin(), xs.begin() + xs.size() / 2, xs.end());
    auto left = [mid = xs[xs.size() / 2]](const gpu::vec4& c) { return c.x < mid; };
    double largest = largest_kinetic_energy(sim), largest_left = largest_kinetic_energy(sim, left);
    CHECK(device.state_downloads() == at_start);
    CHECK(sim.kinetic_energy().total() > 0);  // the first reading downloads the state
    CHECK(device.state_downloads() == at_start + 1);
    CHECK(same_rows_in_slots(any, sim));
    // From the state by global id: the same largest, to the bit (a largest knows no order).
    CHECK(largest > 0);
    CHECK(largest_kinetic_energy(sim) == largest);
    CHECK((largest_left > 0 && largest_left <= largest));
    CHECK(largest_kinetic_energy(sim, left) == largest_left);
    CHECK(largest_kinetic_energy(sim, [](const gpu::vec4&) { return false; }) == 0);
    sim.contact_forces();
    CHECK(device.state_downloads() == at_start + 1);  // read already: not again
    sim.advance(100);
    CHECK(device.state_downloads() == at_start + 1);
    sim.state();
    CHECK(device.state_downloads() == at_start + 2);
  }
}

TEST_CASE("lazy download: a long run nobody reads downloads every 32 batches, so an overflow replays no more",
          "[engine][lazy]") {
  Model model = build_model(bench_bed_case(2000));
  KernelVariant case_order = KernelVariant::parse("reorder=0");  // no reorder reads the state
  for (const char* backend : {"cpu", "vulkan"}) {
    INFO(backend);
    Simulation sim(model, make_backend(backend, -1, 1, case_order.workgroup), case_order, 50);
    uint64_t at_start = sim.backend().state_downloads();
    sim.advance(31 * 50);
    CHECK(sim.backend().state_downloads() == at_start);
    sim.advance(50);
    CHECK(sim.backend().state_downloads() == at_start + 1);
    sim.state();  // that download is the state after the 32nd batch
    CHECK(sim.backend().state_downloads() == at_start + 1);
  }
}
