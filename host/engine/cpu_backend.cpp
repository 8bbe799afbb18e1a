#include "engine/cpu_backend.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <new>

#include <sys/mman.h>

#include "contact_lanes.h"
#include "lane_switches.h"
#include "twin_kernels.h"
#include "walk_lanes.h"
#include "engine/buffer_table.h"

namespace repose {

CpuBackend::CpuBackend(unsigned threads) : pool_(threads) {}

std::string CpuBackend::describe() const {
  std::string lanes = gpu::lanes_enabled(gpu::LaneKernels::Contacts)
                          ? std::string(", contacts in ") + gpu::contact_lanes_target() + " lanes"
                          : std::string(", contacts one at a time");
  if (!gpu::lanes_enabled(gpu::LaneKernels::Kick)) lanes += ", the kick one particle at a time";
  if (!gpu::lanes_enabled(gpu::LaneKernels::Bodies)) lanes += ", the bodies' kernels one at a time";
  if (!gpu::lanes_enabled(gpu::LaneKernels::Neighbours)) lanes += ", the neighbour list as the shaders build it";
  return "cpu (C++ twin of the shaders, " + std::to_string(pool_.size()) + " thread" +
         (pool_.size() == 1 ? "" : "s") + lanes + ")";
}

void CpuBackend::FreeArena::operator()(std::byte* p) const { std::free(p); }

std::unique_ptr<std::byte, CpuBackend::FreeArena> CpuBackend::zeroed_arena(size_t bytes) {
  constexpr size_t kHuge = size_t(2) << 20;
  void* p = nullptr;
  if (bytes >= kHuge && posix_memalign(&p, kHuge, (bytes + kHuge - 1) / kHuge * kHuge) == 0)
    madvise(p, bytes, MADV_HUGEPAGE);  // advice only: without huge pages the memory is as good
  else
    p = std::malloc(bytes);
  if (!p) throw std::bad_alloc();
  std::memset(p, 0, bytes);
  return std::unique_ptr<std::byte, FreeArena>(static_cast<std::byte*>(p));
}

void CpuBackend::allocate(const Layout& l, const ConstantData& constants) {
  layout_ = l;
  arena_.reset();  // the old buffers go first, so a larger list never holds both
  std::array<size_t, gpu::kBindingCount> offset{};
  size_t total = 0;
  for (uint32_t b = 0; b < gpu::kBindingCount; ++b) {
    offset[b] = total;
    storage_[b].length = std::max<size_t>(binding_bytes(b, l), 16);
    total += (storage_[b].length + 63) / 64 * 64;  // each binding on its own cache lines
  }
  walk_rows_ = {nullptr, gpu::walk_rows_floats(l.n_particles) * sizeof(float)};  // Buffers::walk_rows
  const size_t walk_rows_at = total;
  total += walk_rows_.length;
  arena_ = zeroed_arena(total);
  for (uint32_t b = 0; b < gpu::kBindingCount; ++b) storage_[b].begin = arena_.get() + offset[b];
  walk_rows_.begin = arena_.get() + walk_rows_at;
  point_buffers();
  upload_constants(constants);
}

void CpuBackend::upload_constants(const ConstantData& constants) {
  for_each_constant(constants, [&](const BufferSpec& b, const auto& v) { put(b.binding, v); });
  const uint32_t* m = buf_.material;
  const uint32_t n = layout_.n_particles;
  buf_.uniform_material = n > 0 && std::all_of(m, m + n, [&](uint32_t x) { return x == m[0]; }) ? int32_t(m[0]) : -1;
}

void CpuBackend::point_buffers() {
#define REPOSE_POINT(binding, Name, name, type, count, need, keep) \
  buf_.name = reinterpret_cast<gpu::type*>(storage_[binding].data());
  REPOSE_BUFFERS(REPOSE_POINT)
#undef REPOSE_POINT
  buf_.walk_rows = reinterpret_cast<float*>(walk_rows_.data());
}

template <class T>
void CpuBackend::put(uint32_t binding, const std::vector<T>& src) {
  std::memcpy(storage_[binding].data(), src.data(), std::min(src.size() * sizeof(T), storage_[binding].size()));
}

void CpuBackend::upload_state(const HostState& s) {
  for_each_kept(s, [&](const BufferSpec& b, const auto& v) { put(b.binding, v); });
}

void CpuBackend::read_binding(uint32_t binding, void* dst, size_t bytes) {
  std::memcpy(dst, storage_[binding].data(), std::min(bytes, storage_[binding].size()));
}

void CpuBackend::read_state(HostState& s) {
  for_each_kept(s, [&](const BufferSpec& b, auto& v) {
    using T = typename std::decay_t<decltype(v)>::value_type;
    const T* data = reinterpret_cast<const T*>(storage_[b.binding].data());
    v.assign(data, data + used_elements(b, layout_, s));
  });
}

void CpuBackend::upload_walls(const std::vector<gpu::WallState>& rows, size_t first) {
  const Binding& block = storage_[gpu::kBindWalls];
  size_t offset = std::min(first * sizeof(gpu::WallState), block.size());
  std::memcpy(block.data() + offset, rows.data(), std::min(rows.size() * sizeof(gpu::WallState), block.size() - offset));
}

void CpuBackend::execute(const std::vector<Dispatch>& program, ExecuteTimes* times) {
  for (const Dispatch& d : program) {
    auto t0 = std::chrono::steady_clock::now();
    // Indirect arguments hold rows of workgroups (gpu::dispatch_rows): x times y groups.
    uint64_t groups = d.indirect_word >= 0
                          ? uint64_t(buf_.control[d.indirect_word]) * buf_.control[d.indirect_word + 1]
                          : d.groups;
    if (d.kernel == KernelId::Scan) {
      if (groups > 0) gpu::run_scan(buf_, d.scan, pool_);
    } else if (d.kernel == KernelId::WallReduce) {  // a fixed tree per wall, as the shader's
      buf_.push = d.sim;
      gpu::run_wall_reduce(buf_);
    } else {
      buf_.push = d.sim;
      gpu::run_kernel(d.kernel, buf_, uint64_t(groups) * d.sim.workgroup, pool_);
    }
    if (times)
      times->kernels[kernel_shader_name(d.kernel)] +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
}

std::vector<uint32_t> CpuBackend::read_control() {
  return std::vector<uint32_t>(buf_.control, buf_.control + gpu::kControlWords);
}

std::vector<gpu::vec4> CpuBackend::wall_forces(const gpu::SimPush& push) {
  buf_.push = push;
  gpu::run_wall_reduce(buf_);
  return std::vector<gpu::vec4>(buf_.wall_force, buf_.wall_force + layout_.n_wall_groups);
}

std::vector<gpu::vec4> CpuBackend::wall_sums() {
  size_t n = layout_.n_wall_groups;
  return std::vector<gpu::vec4>(buf_.wall_force + n, buf_.wall_force + 3 * n);
}

std::vector<gpu::vec4> CpuBackend::contact_forces(uint32_t contacts) {
  return std::vector<gpu::vec4>(buf_.contact_force, buf_.contact_force + std::min(contacts, layout_.capacity));
}

size_t CpuBackend::memory_bytes() const {
  size_t bytes = 0;
  for (const auto& block : storage_) bytes += block.size();
  return bytes + walk_rows_.size();
}

double CpuBackend::contact_law_seconds_per_contact() {
  const uint32_t flags = buf_.push.flags;  // free spheres only: a clump's levers are gathered from its body
  if (!gpu::contact_lanes_cover(flags) || (flags & gpu::kFlagBodies) != 0u || buf_.control[gpu::kCtlContacts] == 0) return 0;
  gpu::Kernels k(buf_);
  const size_t width = gpu::contact_lanes_width();
  const uint64_t batches = uint64_t(1) << 17;  // 2M contacts at 16 lanes: ~10 ms a pass
  double best = 0;
  for (int pass = 0; pass < 5; ++pass) {
    auto t0 = std::chrono::steady_clock::now();
    pool_.parallel_for(batches, [&](uint64_t begin, uint64_t end) {
      std::vector<float> sink(gpu::kLawRing * gpu::kSinkFloats * width);
      gpu::contact_law_lanes(k, end - begin, sink.data());
    });
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    best = pass == 0 ? seconds : std::min(best, seconds);
  }
  return best / double(batches * width);
}

}  // namespace repose
