// The CPU twin of the compute shaders: the same kernel bodies (shaders/kernels/*.h) compiled as
// C++ and run over a thread pool. Buffers are plain arrays laid out exactly as on the device.
#pragma once
#include <cstdint>

#include "kernel_ids.h"
#include "repose_shared.h"
#include "thread_pool.h"

namespace repose::gpu {

// Pointers to every buffer of the descriptor set, in the shaders' names (B_pos -> pos, ...).
struct Buffers {
  vec4* pos = nullptr;
  vec4* vel = nullptr;
  vec4* omega = nullptr;
  vec4* force = nullptr;
  vec4* torque = nullptr;
  vec4* pos_at_build = nullptr;
  uint* material = nullptr;
  PairParams* pairs = nullptr;
  WallState* walls = nullptr;
  uint* control = nullptr;
  uint* cell_of = nullptr;
  uint* cell_start = nullptr;
  uint* cell_fill = nullptr;
  uint* sorted = nullptr;
  uint* row_start = nullptr;
  uint* partner = nullptr;
  uint* owner = nullptr;
  vec4* history = nullptr;
  uint* old_row_start = nullptr;
  uint* old_partner = nullptr;
  vec4* old_history = nullptr;
  vec4* contact_force = nullptr;
  vec4* torque_i = nullptr;
  vec4* torque_j = nullptr;
  uint* trans_start = nullptr;
  uint* trans_fill = nullptr;
  uint* trans_list = nullptr;
  vec4* wall_force = nullptr;
  Body* bodies = nullptr;
  SubSphere* subs = nullptr;
  vec4* rolling_spring = nullptr;
  SimPush push{};
};

// Runs `invocations` invocations of kernel k (as a dispatch of that many threads would).
void run_kernel(KernelId k, Buffers& buf, uint64_t invocations, ThreadPool& pool);
// The single-workgroup scan and the per-wall reduction, in the shaders' exact arithmetic order.
void run_scan(Buffers& buf, const ScanPush& push);
void run_wall_reduce(Buffers& buf, uint n_walls);

}  // namespace repose::gpu
