// The CPU twin of the compute shaders: the same kernel bodies (shaders/kernels/*.h) compiled as
// C++ and run over a thread pool. Buffers are plain arrays laid out exactly as on the device.
#pragma once
#include <cstdint>

#include "kernel_ids.h"
#include "repose_shared.h"
#include "thread_pool.h"

namespace repose::gpu {

// Pointers to every buffer of the table in repose_shared.h (the shaders' B_pos is pos here; the
// kernel bodies see them under the shaders' names as members of Kernels, twin_kernels.h).
struct Buffers {
#define REPOSE_BUFFER_POINTER(binding, Name, name, type, count, need, keep) type* name = nullptr;
  REPOSE_BUFFERS(REPOSE_BUFFER_POINTER)
#undef REPOSE_BUFFER_POINTER
  SimPush push{};
  // Not a device buffer: the material of every particle when they share one (else -1), so that the
  // contact lanes gather none (CpuBackend::upload_constants; the walls' materials may differ).
  int32_t uniform_material = -1;
  // Not a device buffer: the sorted slots' positions, radii and global ids as five arrays (x, y, z,
  // radius, id; N floats each, then a vector's width of padding), which contact_count's lanes fill
  // and walk (walk_lanes.h); null: the scalar walk.
  float* walk_rows = nullptr;
};

// Runs `invocations` invocations of kernel k (as a dispatch of that many threads would).
void run_kernel(KernelId k, Buffers& buf, uint64_t invocations, ThreadPool& pool);
// One pass of the scan (shaders/scan.comp; integer sums, so plain loops give its bytes; the
// block passes over the pool) and the reduction per named wall, in the shader's exact arithmetic order.
void run_scan(Buffers& buf, const ScanPush& push, ThreadPool& pool);
void run_wall_reduce(Buffers& buf);

}  // namespace repose::gpu
