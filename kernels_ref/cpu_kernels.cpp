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
#define PC buf.push
#define KERNEL(name) inline void name(Buffers& buf,
#define KFN(ret, name) inline ret name(Buffers& buf,
#define KB buf,

#include "kernels/all.h"

using KernelBody = void (*)(Buffers&, uint);

static KernelBody body_of(KernelId k) {
  switch (k) {
    case KernelId::KickDrift: return k_kick_drift;
    case KernelId::GatherKick: return k_gather_kick;
    case KernelId::RebuildArgs: return [](Buffers& b, uint i) { if (i == 0u) k_rebuild_args(b, 0u); };
    case KernelId::SaveOldRows: return k_save_old_rows;
    case KernelId::SaveOldContacts: return k_save_old_contacts;
    case KernelId::ClearBuckets: return k_clear_buckets;
    case KernelId::BucketCount: return k_bucket_count;
    case KernelId::BucketScatter: return k_bucket_scatter;
    case KernelId::BucketSort: return k_bucket_sort;
    case KernelId::ContactCount: return k_contact_count;
    case KernelId::RowsScanned: return [](Buffers& b, uint i) { if (i == 0u) k_rows_scanned(b, 0u); };
    case KernelId::ContactFill: return k_contact_fill;
    case KernelId::TransposeCount: return k_transpose_count;
    case KernelId::TransposeFill: return k_transpose_fill;
    case KernelId::TransposeSort: return k_transpose_sort;
    case KernelId::ContactForces: return k_contact_forces;
    case KernelId::ContactRows: return k_contact_rows;
    case KernelId::GatherLean: return k_gather_lean;
    default: return nullptr;
  }
}

void run_kernel(KernelId k, Buffers& buf, uint64_t invocations, ThreadPool& pool) {
  KernelBody body = body_of(k);
  // Single-invocation control kernels must not run on several threads at once.
  if (k == KernelId::RebuildArgs || k == KernelId::RowsScanned) {
    if (invocations > 0) body(buf, 0u);
    return;
  }
  pool.parallel_for(invocations, [&](uint64_t begin, uint64_t end) {
    for (uint64_t i = begin; i < end; ++i) body(buf, static_cast<uint>(i));
  });
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
  uint total = buf.control[kCtlContacts];
  for (uint w = 0; w < n_walls; ++w) {
    uint partner = buf.push.n_particles + w;
    float sx[W], sy[W], sz[W];
    for (uint t = 0; t < W; ++t) {
      vec3 acc(0.0f);
      for (uint c = t; c < total; c += W)
        if (buf.partner[c] == partner) acc = acc - xyz(buf.contact_force[c]);
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
