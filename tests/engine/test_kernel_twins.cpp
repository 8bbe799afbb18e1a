// Per-kernel twin test: the same seeded state on lavapipe and on the CPU twin, then one step's
// program run one dispatch at a time on both; after every dispatch every buffer it can touch
// must be identical to the byte. Sizes straddle the workgroup (n = WG-1, WG, WG+1, 2 WG+1).
#include <catch2/catch.hpp>
#include <cstring>
#include <random>

#include "engine/buffer_table.h"
#include "engine/cpu_backend.h"
#include "engine/step_program.h"
#include "engine/vulkan_backend.h"
#include "engine_test_support.h"

using namespace repose;
using namespace repose::test;

namespace {

struct Binding {
  uint32_t index;
  const char* name;
  size_t bytes;
  const void* cpu;
};

// Every buffer the kernels write, and the inputs that change during a run (the id table, the
// walls), with its size in this layout and the twin's copy.
std::vector<Binding> twin_bindings(const Layout& l, const gpu::Buffers& b) {
  size_t N = l.n_particles, C = l.capacity, T = l.table_size, v4 = 16, u = 4;
  std::vector<Binding> bindings = {
      {gpu::kBindPos, "pos", N * v4, b.pos}, {gpu::kBindVel, "vel", N * v4, b.vel},
      {gpu::kBindOmega, "omega", N * v4, b.omega}, {gpu::kBindForce, "force", N * v4, b.force},
      {gpu::kBindTorque, "torque", N * v4, b.torque}, {gpu::kBindPosAtBuild, "pos_at_build", N * v4, b.pos_at_build},
      {gpu::kBindControl, "control", gpu::kControlWords * u, b.control},
      {gpu::kBindCellOf, "cell_of", N * u, b.cell_of}, {gpu::kBindCellStart, "cell_start", (T + 1) * u, b.cell_start},
      {gpu::kBindCellFill, "cell_fill", (T + 1) * u, b.cell_fill},
      {gpu::kBindSorted, "sorted", N * u, b.sorted}, {gpu::kBindRowStart, "row_start", (N + 1) * u, b.row_start},
      {gpu::kBindPartner, "partner", C * u, b.partner}, {gpu::kBindOwner, "owner", C * u, b.owner},
      {gpu::kBindHistory, "history", C * v4, b.history}, {gpu::kBindContactForce, "contact_force", C * v4, b.contact_force},
      {gpu::kBindTorqueI, "torque_i", C * v4, b.torque_i}, {gpu::kBindTransStart, "trans_start", (N + 1) * u, b.trans_start},
      {gpu::kBindTransList, "trans_list", C * u, b.trans_list}, {gpu::kBindIds, "ids", 2 * N * u, b.ids},
      {gpu::kBindWalls, "walls", buffer_elements(kBufferTable[kRowWalls], l) * sizeof(gpu::WallState), b.walls},
      {gpu::kBindScanBlocks, "scan_blocks", buffer_elements(kBufferTable[kRowScanBlocks], l) * u, b.scan_blocks},
  };
  if (l.n_bodies) bindings.push_back({gpu::kBindBodies, "bodies", l.n_bodies * sizeof(gpu::Body), b.bodies});
  if (l.n_parts) bindings.push_back({gpu::kBindParts, "parts", l.n_parts * sizeof(gpu::BodyPart), b.parts});
  return bindings;
}

// The program with every scan in its three block passes, as a large case's (a small one's scans
// take one workgroup: scan_in_blocks).
std::vector<Dispatch> with_block_scans(const std::vector<Dispatch>& program) {
  std::vector<Dispatch> out;
  for (const Dispatch& d : program) {
    if (d.kernel != KernelId::Scan) out.push_back(d);
    else
      for (const Dispatch& pass : scan_dispatches(d.scan.target, d.scan.count, true)) out.push_back(pass);
  }
  return out;
}

// Runs one step of `spec` (after `warmup` steps in batches of `batch`, forcing a rebuild) one
// dispatch at a time on both backends and requires every buffer to match after every dispatch.
// The walls must be at rest (the step reads wall slot 0 of the last batch).
void check_each_dispatch(const CaseSpec& spec, const char* variant_text, uint64_t warmup, uint32_t batch,
                         const std::string& label, bool block_scans = false) {
  KernelVariant v = KernelVariant::parse(variant_text);
  auto cpu_sim = simulate(spec, "cpu", 2, v, batch);
  auto gpu_sim = simulate(spec, "vulkan", 1, v, batch);
  cpu_sim->advance(warmup);  // histories (and clump contacts) are non-zero
  gpu_sim->advance(warmup);
  auto& cpu = dynamic_cast<CpuBackend&>(cpu_sim->backend());
  auto& gpu = dynamic_cast<VulkanBackend&>(gpu_sim->backend());
  const Layout& l = cpu_sim->layout();
  REQUIRE(l.capacity == gpu_sim->layout().capacity);
  // Force the next step to rebuild, so the neighbour kernels run too.
  HostState s = cpu_sim->state();
  s.control[gpu::kCtlNeedRebuild] = 1;
  cpu_sim->set_state(s);
  gpu_sim->set_state(s);

  std::vector<Binding> bindings = twin_bindings(l, cpu.buffers());
  auto program = step_program(cpu_sim->model(), l, v, 0);
  if (block_scans) program = with_block_scans(program);
  size_t checked = 0;
  for (const Dispatch& d : program) {
    cpu.execute({d}, nullptr);
    gpu.execute({d}, nullptr);
    for (const Binding& bind : bindings) {
      // The two scatters place ids by atomic cursor, in thread order; the sort kernel right
      // after them fixes the order, and the comparison happens there.
      bool scattered = (d.kernel == KernelId::BucketScatter && bind.index == gpu::kBindSorted) ||
                       (d.kernel == KernelId::TransposeFill && bind.index == gpu::kBindTransList);
      if (scattered) {
        ++checked;
        continue;
      }
      std::vector<char> from_gpu(bind.bytes);
      gpu.read_binding(bind.index, from_gpu.data(), bind.bytes);
      bool same = std::memcmp(from_gpu.data(), bind.cpu, bind.bytes) == 0;
      INFO(label << ", " << variant_text << ": after " << kernel_shader_name(d.kernel) << ", buffer " << bind.name
                 << " differs");
      REQUIRE(same);
      ++checked;
    }
  }
  CHECK(checked == program.size() * bindings.size());
  CHECK(cpu.read_control()[gpu::kCtlRebuildCount] >= 2);  // the forced rebuild happened
}

// Each dispatch of a step alone, from identical inputs: before every dispatch the device gets
// the twin's buffers, so a difference names the kernel whose own arithmetic differs (on a GPU
// that rounds a division or square root its own way, say), not one inherited from an earlier
// kernel. Prints a table of kernel, buffer, differing words and the largest difference in ULPs.
void check_each_kernel_alone(const CaseSpec& spec, const char* variant_text, uint64_t warmup, uint32_t batch,
                             const std::string& label) {
  KernelVariant v = KernelVariant::parse(variant_text);
  auto cpu_sim = simulate(spec, "cpu", 2, v, batch);
  auto gpu_sim = simulate(spec, "vulkan", 1, v, batch);
  cpu_sim->advance(warmup);
  gpu_sim->store_in_order(cpu_sim->particle_order());  // the same slots: the buffers are copied over
  HostState s = cpu_sim->state();
  s.control[gpu::kCtlNeedRebuild] = 1;
  cpu_sim->set_state(s);
  gpu_sim->set_state(s);
  auto& cpu = dynamic_cast<CpuBackend&>(cpu_sim->backend());
  auto& gpu = dynamic_cast<VulkanBackend&>(gpu_sim->backend());
  const Layout& l = cpu_sim->layout();
  std::vector<Binding> bindings = twin_bindings(l, cpu.buffers());
  std::vector<std::string> differences;
  for (const Dispatch& d : step_program(cpu_sim->model(), l, v, 0)) {
    for (const Binding& bind : bindings) gpu.write_binding(bind.index, bind.cpu, bind.bytes);
    cpu.execute({d}, nullptr);
    gpu.execute({d}, nullptr);
    for (const Binding& bind : bindings) {
      bool scattered = (d.kernel == KernelId::BucketScatter && bind.index == gpu::kBindSorted) ||
                       (d.kernel == KernelId::TransposeFill && bind.index == gpu::kBindTransList);
      if (scattered) continue;
      std::vector<int32_t> g(bind.bytes / 4), c(bind.bytes / 4);
      gpu.read_binding(bind.index, g.data(), bind.bytes);
      std::memcpy(c.data(), bind.cpu, bind.bytes);
      size_t words = 0;
      int64_t ulps = 0;
      for (size_t k = 0; k < g.size(); ++k)
        if (g[k] != c[k]) ++words, ulps = std::max<int64_t>(ulps, std::llabs(int64_t(g[k]) - int64_t(c[k])));
      if (words)
        differences.push_back(label + ", " + variant_text + ": " + kernel_shader_name(d.kernel) + " -> " + bind.name +
                              ": " + std::to_string(words) + " of " + std::to_string(g.size()) + " words, up to " +
                              std::to_string(ulps) + " ULP");
    }
  }
  for (const auto& line : differences) std::printf("kernel alone differs: %s\n", line.c_str());
  INFO(label << ", " << variant_text << ": " << differences.size() << " kernel/buffer pairs differ");
  CHECK(differences.empty());
}

}  // namespace

TEST_CASE("each kernel alone, from the twin's own buffers, gives the twin's bytes", "[engine][bitexact]") {
  check_each_kernel_alone(seeded_cloud(129, 129, 2.05, 0.0), "contact", 3, 1, "cloud");
  check_each_kernel_alone(seeded_cloud(129, 129, 2.05, 0.0), "rows,lean", 3, 1, "cloud");
  check_each_kernel_alone(clump_pile(), "contact", 1500, 100, "clump pile");
}

TEST_CASE("every kernel of a step: lavapipe equals the CPU twin after each dispatch", "[engine][bitexact]") {
  for (const char* variant_text : {"contact", "rows,lean"}) {
    for (uint32_t n : {63u, 64u, 65u, 129u}) {
      // Spacing 2.05 radii: many pairs already touching, so every kernel has real work.
      check_each_dispatch(seeded_cloud(n, n, 2.05, 0.0), variant_text, 3, 1, "n = " + std::to_string(n));
    }
  }
}

// The scans in their block passes (shaders/scan.comp), as a large case runs them: 2,100 spheres
// scan 2 blocks of rows and 5 of buckets, each pass's block sums compared too.
TEST_CASE("every kernel of a step with the scans in block passes: lavapipe equals the CPU twin", "[engine][bitexact]") {
  REQUIRE(gpu::scan_blocks_for(2100) == 2);
  for (const char* variant_text : {"contact", "rows,lean"})
    check_each_dispatch(seeded_cloud(2100, 2100, 2.05, 0.0), variant_text, 3, 1, "n = 2100", true);
}

// Clumps rolling against each other and the walls with EDEM's centre-of-mass lever (the default):
// the full kernel and the lean gather compute the lever on both backends alike.
TEST_CASE("every kernel of a clump step, rolling lever at the centre of mass: lavapipe equals the CPU twin",
          "[engine][bitexact]") {
  CaseSpec pile = clump_pile();
  pile.neighbour.body_broad_phase = true;  // its part_place and part_near run too
  REQUIRE(pile.contact.rolling_lever == RollingLever::Centre);
  for (const char* variant_text : {"contact", "contact,lean", "rows,lean"})
    check_each_dispatch(pile, variant_text, 1500, 100, "clump pile");
}
