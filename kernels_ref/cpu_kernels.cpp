// Compiles the shared kernel bodies as C++. Must stay at -ffp-contract=off (see CMakeLists.txt).
#include "cpu_kernels.h"

#include "contact_lanes.h"
#include "twin_kernels.h"

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

void run_kernel(KernelId id, Buffers& buf, uint64_t invocations, ThreadPool& pool) {
  if (invocations == 0) return;
  Kernels k(buf);
  uint limit = buf.control[kCtlContacts];
  if (id == KernelId::ContactForces && contact_lanes_cover(buf.push.flags))
    return run_contact_lanes(k, std::min<uint64_t>(invocations, limit), pool);
  if (id == KernelId::ContactRows && contact_lanes_cover(buf.push.flags))
    return run_contact_lanes(k, std::min(buf.row_start[buf.push.n_particles], limit), pool);
  // Single-invocation control kernels must not run on several threads at once.
  if (id == KernelId::RebuildArgs) return k.k_rebuild_args(0u);
  if (id == KernelId::RowsScanned) return k.k_rows_scanned(0u);
  switch (id) {
    case KernelId::KickDrift: return run_parallel<&Kernels::k_kick_drift>(k, invocations, pool);
    case KernelId::GatherKick: return run_parallel<&Kernels::k_gather_kick>(k, invocations, pool);
    case KernelId::GatherLean: return run_parallel<&Kernels::k_gather_lean>(k, invocations, pool);
    case KernelId::SaveOldRows: return run_parallel<&Kernels::k_save_old_rows>(k, invocations, pool);
    case KernelId::SaveOldContacts: return run_parallel<&Kernels::k_save_old_contacts>(k, invocations, pool);
    case KernelId::ClearBuckets: return run_parallel<&Kernels::k_clear_buckets>(k, invocations, pool);
    case KernelId::BucketCount: return run_parallel<&Kernels::k_bucket_count>(k, invocations, pool);
    case KernelId::BucketScatter: return run_parallel<&Kernels::k_bucket_scatter>(k, invocations, pool);
    case KernelId::BucketSort: return run_parallel<&Kernels::k_bucket_sort>(k, invocations, pool);
    case KernelId::ContactCount: return run_parallel<&Kernels::k_contact_count>(k, invocations, pool);
    case KernelId::ContactFill: return run_parallel<&Kernels::k_contact_fill>(k, invocations, pool);
    case KernelId::TransposeCount: return run_parallel<&Kernels::k_transpose_count>(k, invocations, pool);
    case KernelId::TransposeFill: return run_parallel<&Kernels::k_transpose_fill>(k, invocations, pool);
    case KernelId::TransposeSort: return run_parallel<&Kernels::k_transpose_sort>(k, invocations, pool);
    case KernelId::ContactForces: return run_parallel<&Kernels::k_contact_forces>(k, invocations, pool);
    case KernelId::ContactRows: return run_parallel<&Kernels::k_contact_rows>(k, invocations, pool);
    case KernelId::BodyKickDrift: return run_parallel<&Kernels::k_body_kick_drift>(k, invocations, pool);
    case KernelId::BodyPlace: return run_parallel<&Kernels::k_body_place>(k, invocations, pool);
    case KernelId::BodyGatherKick: return run_parallel<&Kernels::k_body_gather_kick>(k, invocations, pool);
    default: return;
  }
}

void run_scan(Buffers& buf, const ScanPush& push) {
  uint* data = push.target == kScanCells ? buf.cell_start
             : push.target == kScanRows  ? buf.row_start
                                         : buf.trans_start;
  uint sum = 0u;
  for (uint k = 0; k < push.count; ++k) {
    uint v = data[k];
    data[k] = sum;
    sum += v;
  }
  data[push.count] = sum;
}

void run_wall_reduce(Buffers& buf, uint n_walls) {
  constexpr uint W = kWallReduceWorkgroup;
  Kernels k(buf);
  uint limit = buf.control[kCtlContacts];
  for (uint w = 0; w < n_walls; ++w) {
    uint partner = buf.push.n_particles + w;
    float sx[W], sy[W], sz[W];
    for (uint t = 0; t < W; ++t) {
      vec3 acc(0.0f);
      for (uint i = t; i < buf.push.n_particles; i += W) {
        uint end = min(buf.row_start[i + 1u], limit);
        for (uint c = min(buf.row_start[i], limit); c < end; ++c)
          if (buf.partner[c] == partner) acc = acc - k.xyz(buf.contact_force[c]);
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
