// Compiles the shared kernel bodies as C++. Must stay at -ffp-contract=off (see CMakeLists.txt).
#include "cpu_kernels.h"

#include <algorithm>

#include "body_lanes.h"
#include "contact_lanes.h"
#include "kick_lanes.h"
#include "lane_switches.h"
#include "twin_kernels.h"
#include "walk_lanes.h"

namespace repose::gpu {

// Runs invocations [0, n) of kernel Body over the pool; a template so that the body inlines into
// the loop (no indirect call per invocation, which costs ~0.1 ms per 50k-particle kernel).
template <void (Kernels::*Body)(uint)>
static void run_parallel(Kernels& k, uint64_t n, ThreadPool& pool) {
  pool.parallel_for(n, [&](uint64_t begin, uint64_t end) {
    for (uint64_t i = begin; i < end; ++i) (k.*Body)(static_cast<uint>(i));
  });
}

// The contact kernel over contacts [0, end) in SIMD lanes (contact_lanes.h): both variants
// compute each contact alone, so the owner rows' split does not matter.
static void run_contact_lanes(Kernels& k, uint64_t end, ThreadPool& pool) {
  pool.parallel_for(end, [&](uint64_t begin, uint64_t stop) { contact_forces_lanes(k, begin, stop); });
}

// A kernel whose lanes take invocations [begin, end) (body_lanes.h), over the pool.
template <void (*Lanes)(Kernels&, uint64_t, uint64_t)>
static void run_lanes(Kernels& k, uint64_t n, ThreadPool& pool) {
  pool.parallel_for(n, [&](uint64_t begin, uint64_t end) { Lanes(k, begin, end); });
}

// transpose_count with plain additions on one thread: the atomic additions of the kernel's
// threads cost more than the whole pass (the same counts).
static void count_transposed(Kernels& k) {
  const uint n = k.PC.n_particles, used = k.B_control[kCtlContacts];
  for (uint c = 0; c < used; ++c) {
    const uint p = k.B_partner[c];
    if (p < n) k.B_trans_start[p] += 1u;
  }
}

// transpose_fill with each transposed row filled in its owners' global id order (the owners
// visited by id): the rows come out as transpose_sort leaves them, with no atomic cursor and no
// sort (the trans_fill counters end as the kernel's do). One thread: split by partners' ranges
// over two, each reading every row, it measured no faster.
static void fill_transposed_in_order(Kernels& k) {
  const uint n = k.PC.n_particles, used = k.B_control[kCtlContacts];
  for (uint g = 0; g < n; ++g) {
    const uint i = k.slot_of(g), end = min(k.B_row_start[i + 1u], used);
    for (uint c = min(k.B_row_start[i], used); c < end; ++c) {
      const uint p = k.B_partner[c];
      if (p < n) k.B_trans_list[k.B_trans_start[p] + k.B_trans_fill[p]++] = c;
    }
  }
}

void run_kernel(KernelId id, Buffers& buf, uint64_t invocations, ThreadPool& pool) {
  if (invocations == 0) return;
  Kernels k(buf);
  if (id == KernelId::BodyPlace && lanes_enabled(LaneKernels::Bodies)) return run_lanes<body_place_lanes>(k, invocations, pool);
  if (id == KernelId::BodyGatherKick && lanes_enabled(LaneKernels::Bodies))
    return run_lanes<body_gather_kick_lanes>(k, invocations, pool);
  if (id == KernelId::KickDrift && lanes_enabled(LaneKernels::Kick)) return run_lanes<kick_drift_lanes>(k, invocations, pool);
  if (id == KernelId::GatherKick && lanes_enabled(LaneKernels::Kick)) return run_lanes<gather_kick_lanes>(k, invocations, pool);
  if (id == KernelId::ContactCount && buf.walk_rows && lanes_enabled(LaneKernels::Neighbours)) {
    run_lanes<fill_walk_rows>(k, buf.cell_start[buf.push.table_size + 1u], pool);  // the slots bucket_scatter filled
    return run_lanes<contact_count_lanes>(k, invocations, pool);
  }
  if (id == KernelId::ContactFill && lanes_enabled(LaneKernels::Neighbours))
    return run_lanes<contact_fill_lanes>(k, invocations, pool);
  if (id == KernelId::TransposeCount && lanes_enabled(LaneKernels::Neighbours)) return count_transposed(k);
  if (id == KernelId::TransposeFill && lanes_enabled(LaneKernels::Neighbours)) return fill_transposed_in_order(k);
  if (id == KernelId::TransposeSort && lanes_enabled(LaneKernels::Neighbours)) return;  // in order already
  uint limit = buf.control[kCtlContacts];
  if (id == KernelId::ContactForces && contact_lanes_cover(buf.push.flags))
    return run_contact_lanes(k, std::min<uint64_t>(invocations, limit), pool);
  if (id == KernelId::ContactRows && contact_lanes_cover(buf.push.flags))
    return run_contact_lanes(k, std::min(buf.row_start[buf.push.n_particles], limit), pool);
  // The list in kernel_ids.h: Each over the pool, Once on this thread (a control kernel must not
  // run on several threads at once), Own kernels have entries of their own (run_scan, run_wall_reduce).
  switch (id) {
#define REPOSE_RUN_Each(name) return run_parallel<&Kernels::k_##name>(k, invocations, pool);
#define REPOSE_RUN_Once(name) return k.k_##name(0u);
#define REPOSE_RUN_Own(name) return;
#define REPOSE_RUN(Id, name, kind) \
  case KernelId::Id: REPOSE_RUN_##kind(name)
    REPOSE_KERNELS(REPOSE_RUN)
#undef REPOSE_RUN
#undef REPOSE_RUN_Own
#undef REPOSE_RUN_Once
#undef REPOSE_RUN_Each
    case KernelId::Count: return;
  }
}

// Scans data[begin, end) in place from `carry`; returns the carry after it.
static uint scan_run(uint* data, uint begin, uint end, uint carry) {
  for (uint k = begin; k < end; ++k) {
    uint v = data[k];
    data[k] = carry;
    carry += v;
  }
  return carry;
}

void run_scan(Buffers& buf, const ScanPush& push, ThreadPool& pool) {
  uint* data = push.target == kScanCells ? buf.cell_start
             : push.target == kScanRows  ? buf.row_start
                                         : buf.trans_start;
  uint count = push.count, blocks = scan_blocks_for(count);
  auto block_end = [&](uint64_t b) { return uint(std::min<uint64_t>((b + 1) * kScanBlock, count)); };
  if (push.pass == kScanPassWhole) {
    data[count] = scan_run(data, 0, count, 0u);
  } else if (push.pass == kScanPassSums) {
    pool.parallel_for(blocks, [&](uint64_t begin, uint64_t end) {
      for (uint64_t b = begin; b < end; ++b) {
        uint sum = 0u;
        for (uint k = uint(b) * kScanBlock; k < block_end(b); ++k) sum += data[k];
        buf.scan_blocks[b] = sum;
      }
    });
  } else if (push.pass == kScanPassOffsets) {
    uint total = scan_run(buf.scan_blocks, 0, blocks, 0u);
    buf.scan_blocks[blocks] = total;
    data[count] = total;
  } else {
    pool.parallel_for(blocks, [&](uint64_t begin, uint64_t end) {
      for (uint64_t b = begin; b < end; ++b) scan_run(data, uint(b) * kScanBlock, block_end(b), buf.scan_blocks[b]);
    });
  }
}

void run_wall_reduce(Buffers& buf) {
  constexpr uint W = kWallReduceWorkgroup;
  Kernels k(buf);
  uint limit = buf.control[kCtlContacts];
  for (uint w = 0; w < buf.push.n_wall_groups; ++w) {
    float sx[W], sy[W], sz[W];
    for (uint t = 0; t < W; ++t) {
      vec3 acc(0.0f);
      for (uint g = t; g < buf.push.n_particles; g += W) {
        uint i = k.slot_of(g);
        uint end = min(buf.row_start[i + 1u], limit);
        for (uint c = min(buf.row_start[i], limit); c < end; ++c)
          if (k.partner_in_wall_group(buf.partner[c], w)) acc = acc - k.xyz(buf.contact_force[c]);
      }
      sx[t] = acc.x;
      sy[t] = acc.y;
      sz[t] = acc.z;
    }
    for (uint s = W / 2u; s > 0u; s >>= 1u)
      for (uint t = 0; t < s; ++t) {
        sx[t] = sx[t] + sx[t + s];
        sy[t] = sy[t] + sy[t + s];
        sz[t] = sz[t] + sz[t + s];
      }
    k.store_wall_force(w, vec3(sx[0], sy[0], sz[0]));
  }
}

}  // namespace repose::gpu
