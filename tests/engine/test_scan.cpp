// The scan (shaders/scan.comp) alone, on lavapipe and on the CPU twin: from the same random
// counts both give the plain exclusive prefix sum, on one workgroup and in the three block passes,
// at sizes around a block, past the block sums' own block (the offsets pass then walks several),
// and with the block passes split into rows of workgroups (REPOSE_MAX_GROUPS_X's path). After
// every dispatch the scanned array, the block sums and the control words match to the byte.
#include <catch2/catch.hpp>
#include <cstring>
#include <random>

#include "engine/buffer_table.h"
#include "engine/cpu_backend.h"
#include "engine/step_program.h"
#include "engine/vulkan_backend.h"

using namespace repose;

namespace {

struct ScanCase {
  uint32_t target;
  uint32_t count;
  bool in_blocks;
  uint32_t max_groups_x;
};

std::string describe(const ScanCase& c) {
  return "target " + std::to_string(c.target) + ", " + std::to_string(c.count) + " entries, " +
         (c.in_blocks ? "block passes" : "one workgroup") + ", " + std::to_string(c.max_groups_x) + " groups per row";
}

// The layout whose scan of `target` covers `count` entries: N rows, or T+1 bucket counts.
Layout layout_for(uint32_t target, uint32_t count) {
  Layout l;
  l.n_materials = 1;
  l.n_particles = target == gpu::kScanCells ? 1 : count;
  l.table_size = target == gpu::kScanCells ? count - 1 : 1024;
  return l;
}

uint32_t target_binding(uint32_t target) {
  return target == gpu::kScanCells ? gpu::kBindCellStart : target == gpu::kScanRows ? gpu::kBindRowStart
                                                                                      : gpu::kBindTransStart;
}

uint32_t* twin_array(const gpu::Buffers& b, uint32_t target) {
  return target == gpu::kScanCells ? b.cell_start : target == gpu::kScanRows ? b.row_start : b.trans_start;
}

// The bytes of `binding` on the device equal the twin's `expected` words.
bool device_holds(VulkanBackend& gpu, uint32_t binding, const uint32_t* expected, size_t words) {
  std::vector<uint32_t> got(words);
  gpu.read_binding(binding, got.data(), words * sizeof(uint32_t));
  return std::memcmp(got.data(), expected, words * sizeof(uint32_t)) == 0;
}

void check_scan(VulkanBackend& gpu, CpuBackend& cpu, const ScanCase& c) {
  INFO(describe(c));
  Layout l = layout_for(c.target, c.count);
  cpu.allocate(l, {});
  gpu.allocate(l, {});
  // Counts as contact_count writes them (0 ... 40 per row), and a stale word at [count].
  std::mt19937 rng(c.count * 7u + c.target);
  std::vector<uint32_t> counts(size_t(c.count) + 1);
  for (uint32_t& v : counts) v = rng() % 41u;
  counts[c.count] = 0xdeadbeefu;
  uint32_t* twin = twin_array(cpu.buffers(), c.target);
  std::memcpy(twin, counts.data(), counts.size() * sizeof(uint32_t));
  gpu.write_binding(target_binding(c.target), counts.data(), counts.size() * sizeof(uint32_t));

  // rebuild_args of a first build writes the indirect sizes; then the scan's dispatches.
  Dispatch args;
  args.kernel = KernelId::RebuildArgs;
  args.groups = 1;
  args.sim.n_particles = l.n_particles;
  args.sim.table_size = l.table_size;
  args.sim.workgroup = gpu::kDefaultWorkgroup;
  args.sim.max_groups_x = c.max_groups_x;
  std::vector<Dispatch> program = {args};
  for (const Dispatch& d : scan_dispatches(c.target, c.count, c.in_blocks)) program.push_back(d);
  REQUIRE(program.size() == (c.in_blocks ? 4u : 2u));
  size_t block_words = buffer_elements(kBufferTable[kRowScanBlocks], l);
  for (const Dispatch& d : program) {
    cpu.execute({d}, nullptr);
    gpu.execute({d}, nullptr);
    INFO("after pass " << d.scan.pass);
    CHECK(device_holds(gpu, target_binding(c.target), twin, counts.size()));
    CHECK(device_holds(gpu, gpu::kBindScanBlocks, cpu.buffers().scan_blocks, block_words));
    CHECK(device_holds(gpu, gpu::kBindControl, cpu.buffers().control, gpu::kControlWords));
  }
  uint32_t sum = 0;
  for (uint32_t k = 0; k < c.count; ++k) {
    if (twin[k] != sum) FAIL("entry " << k << " is " << twin[k] << ", its prefix sum " << sum);
    sum += counts[k];
  }
  CHECK(twin[c.count] == sum);
}

}  // namespace

TEST_CASE("the scan on lavapipe equals the CPU twin's and the prefix sum, one workgroup or block passes",
          "[engine][bitexact]") {
  VulkanBackend gpu(0, gpu::kDefaultWorkgroup);
  CpuBackend cpu(2);
  const uint32_t B = gpu::kScanBlock;
  for (bool in_blocks : {false, true})
    for (uint32_t count : {0u, 1u, B - 1, B, B + 1, 5 * B + 17})
      check_scan(gpu, cpu, {gpu::kScanRows, count, in_blocks, gpu::kMaxGroupsX});
  check_scan(gpu, cpu, {gpu::kScanTransposed, 3 * B + 5, true, gpu::kMaxGroupsX});
  check_scan(gpu, cpu, {gpu::kScanCells, 2 * B + 1, true, gpu::kMaxGroupsX});
  // More blocks than one block of block sums holds: the offsets pass walks them block by block.
  REQUIRE(gpu::scan_blocks_for(B * B + 3) > B);
  check_scan(gpu, cpu, {gpu::kScanCells, B * B + 3, true, gpu::kMaxGroupsX});
}

TEST_CASE("the scan's block passes split into rows of workgroups give the same bytes", "[engine][bitexact]") {
  VulkanBackend gpu(0, gpu::kDefaultWorkgroup);
  CpuBackend cpu(2);
  const uint32_t B = gpu::kScanBlock;
  // 6 blocks in rows of 4 (8 workgroups: the last two have no block) and of 1; 3 in rows of 2.
  for (uint32_t max_x : {4u, 1u}) check_scan(gpu, cpu, {gpu::kScanRows, 5 * B + 17, true, max_x});
  check_scan(gpu, cpu, {gpu::kScanCells, 2 * B + 1, true, 2});
}
