// Compiles the shared kernel bodies as C++. Must stay at -ffp-contract=off (see CMakeLists.txt).
#include "cpu_kernels.h"

namespace repose::gpu {

#define B_pos buf.pos
#define B_vel buf.vel
#define B_omega buf.omega
#define B_force buf.force
#define B_torque buf.torque
#define B_pos_at_build buf.pos_at_build
#define B_material buf.material
#define B_pairs buf.pairs
#define B_walls buf.walls
#define B_control buf.control
#define B_cell_of buf.cell_of
#define B_cell_start buf.cell_start
#define B_cell_fill buf.cell_fill
#define B_sorted buf.sorted
#define B_row_start buf.row_start
#define B_partner buf.partner
#define B_owner buf.owner
#define B_history buf.history
#define B_old_row_start buf.old_row_start
#define B_old_partner buf.old_partner
#define B_old_history buf.old_history
#define B_contact_force buf.contact_force
#define B_torque_i buf.torque_i
#define B_torque_j buf.torque_j
#define B_trans_start buf.trans_start
#define B_trans_fill buf.trans_fill
#define B_trans_list buf.trans_list
#define B_wall_force buf.wall_force
#define B_bodies buf.bodies
#define B_subs buf.subs
#define B_rolling_spring buf.rolling_spring
#define B_candidates buf.candidates
#define PC buf.push
#define KERNEL(name) inline void name(Buffers& buf,
#define KFN(ret, name) inline ret name(Buffers& buf,
#define KB buf,

#include "kernels/all.h"

using KernelBody = void (*)(Buffers&, uint);

// Runs invocations [0, n) of Body over the pool; a template so that the body inlines into the
// loop (no indirect call per invocation, which costs ~0.1 ms per 50k-particle kernel).
template <KernelBody Body>
static void run_parallel(Buffers& buf, uint64_t n, ThreadPool& pool) {
  pool.parallel_for(n, [&](uint64_t begin, uint64_t end) {
    for (uint64_t i = begin; i < end; ++i) Body(buf, static_cast<uint>(i));
  });
}

void run_kernel(KernelId k, Buffers& buf, uint64_t invocations, ThreadPool& pool) {
  // Single-invocation control kernels must not run on several threads at once.
  if (k == KernelId::RebuildArgs || k == KernelId::RowsScanned) {
    if (invocations > 0) (k == KernelId::RebuildArgs ? k_rebuild_args : k_rows_scanned)(buf, 0u);
    return;
  }
  if (invocations == 0) return;
  switch (k) {
    case KernelId::KickDrift: return run_parallel<k_kick_drift>(buf, invocations, pool);
    case KernelId::GatherKick: return run_parallel<k_gather_kick>(buf, invocations, pool);
    case KernelId::GatherLean: return run_parallel<k_gather_lean>(buf, invocations, pool);
    case KernelId::SaveOldRows: return run_parallel<k_save_old_rows>(buf, invocations, pool);
    case KernelId::SaveOldContacts: return run_parallel<k_save_old_contacts>(buf, invocations, pool);
    case KernelId::ClearBuckets: return run_parallel<k_clear_buckets>(buf, invocations, pool);
    case KernelId::BucketCount: return run_parallel<k_bucket_count>(buf, invocations, pool);
    case KernelId::BucketScatter: return run_parallel<k_bucket_scatter>(buf, invocations, pool);
    case KernelId::BucketSort: return run_parallel<k_bucket_sort>(buf, invocations, pool);
    case KernelId::ContactCount: return run_parallel<k_contact_count>(buf, invocations, pool);
    case KernelId::ContactFill: return run_parallel<k_contact_fill>(buf, invocations, pool);
    case KernelId::TransposeCount: return run_parallel<k_transpose_count>(buf, invocations, pool);
    case KernelId::TransposeFill: return run_parallel<k_transpose_fill>(buf, invocations, pool);
    case KernelId::TransposeSort: return run_parallel<k_transpose_sort>(buf, invocations, pool);
    case KernelId::ContactForces: return run_parallel<k_contact_forces>(buf, invocations, pool);
    case KernelId::ContactRows: return run_parallel<k_contact_rows>(buf, invocations, pool);
    case KernelId::BodyKickDrift: return run_parallel<k_body_kick_drift>(buf, invocations, pool);
    case KernelId::BodyPlace: return run_parallel<k_body_place>(buf, invocations, pool);
    case KernelId::BodyGatherKick: return run_parallel<k_body_gather_kick>(buf, invocations, pool);
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
  uint limit = buf.control[kCtlContacts];
  for (uint w = 0; w < n_walls; ++w) {
    uint partner = buf.push.n_particles + w;
    float sx[W], sy[W], sz[W];
    for (uint t = 0; t < W; ++t) {
      vec3 acc(0.0f);
      for (uint i = t; i < buf.push.n_particles; i += W) {
        uint end = min(buf.row_start[i + 1u], limit);
        for (uint c = min(buf.row_start[i], limit); c < end; ++c)
          if (buf.partner[c] == partner) acc = acc - xyz(buf.contact_force[c]);
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
    buf.wall_force[w] = vec4(sx[0], sy[0], sz[0], 0.0f);
  }
}

}  // namespace repose::gpu
