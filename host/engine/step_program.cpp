#include "engine/step_program.h"

namespace repose {

std::string KernelVariant::name() const {
  std::string s = contact == ContactKernel::PerContact ? "contact" : "rows";
  s += "-wg" + std::to_string(workgroup);
  if (rebuild_interval) s += "-every" + std::to_string(rebuild_interval);
  return s;
}

gpu::SimPush base_push(const Model& m, const Layout& l, const KernelVariant& v) {
  gpu::SimPush p{};
  p.n_particles = l.n_particles;
  p.n_walls = l.n_walls;
  p.capacity = l.capacity;
  p.table_size = l.table_size;
  p.n_materials = l.n_materials;
  p.flags = m.flags;
  p.wall_slot = 0;
  uint32_t interval = m.max_interval;
  if (v.rebuild_interval && (!interval || v.rebuild_interval < interval)) interval = v.rebuild_interval;
  p.max_interval = interval;
  p.workgroup = v.workgroup;
  p.dt = float(m.dt);
  p.kick = 0.0f;
  p.gx = float(m.gravity[0]);
  p.gy = float(m.gravity[1]);
  p.gz = float(m.gravity[2]);
  p.inv_cell = float(1.0 / m.cell);
  p.skin = float(m.skin);
  p.half_skin_sq = float(0.25 * m.skin * m.skin);
  return p;
}

namespace {

uint32_t groups(uint32_t n, uint32_t wg) { return (n + wg - 1) / wg; }

struct ProgramBuilder {
  std::vector<Dispatch> out;
  gpu::SimPush push;
  void direct(KernelId k, uint32_t g, const gpu::SimPush& p) {
    Dispatch d;
    d.kernel = k;
    d.groups = g;
    d.sim = p;
    out.push_back(d);
  }
  void indirect(KernelId k, uint32_t word) {
    Dispatch d;
    d.kernel = k;
    d.indirect_word = static_cast<int32_t>(word);
    d.sim = push;
    out.push_back(d);
  }
  void scan(uint32_t target, uint32_t count) {
    Dispatch d;
    d.kernel = KernelId::Scan;
    d.indirect_word = gpu::kCtlArgsOne;
    d.scan = {target, count, push.capacity, push.workgroup};
    out.push_back(d);
  }
  // Rebuilds the contact list when rebuild_args decides so (indirect sizes are 0 otherwise).
  void rebuild(const Layout& l) {
    direct(KernelId::RebuildArgs, 1, push);
    indirect(KernelId::SaveOldRows, gpu::kCtlArgsParticles);
    indirect(KernelId::SaveOldContacts, gpu::kCtlArgsOldContacts);
    indirect(KernelId::ClearBuckets, gpu::kCtlArgsBuckets);
    indirect(KernelId::BucketCount, gpu::kCtlArgsParticles);
    scan(gpu::kScanCells, l.table_size);
    indirect(KernelId::BucketScatter, gpu::kCtlArgsParticles);
    indirect(KernelId::BucketSort, gpu::kCtlArgsBuckets);
    indirect(KernelId::ContactCount, gpu::kCtlArgsParticles);
    scan(gpu::kScanRows, l.n_particles);
    indirect(KernelId::RowsScanned, gpu::kCtlArgsOne);
    indirect(KernelId::ContactFill, gpu::kCtlArgsParticles);
    indirect(KernelId::TransposeCount, gpu::kCtlArgsNewContacts);
    scan(gpu::kScanTransposed, l.n_particles);
    indirect(KernelId::TransposeFill, gpu::kCtlArgsNewContacts);
    indirect(KernelId::TransposeSort, gpu::kCtlArgsParticles);
  }
  void forces(const Layout& l, const KernelVariant& v) {
    if (v.contact == ContactKernel::PerContact)
      indirect(KernelId::ContactForces, gpu::kCtlArgsContacts);
    else
      direct(KernelId::ContactRows, groups(l.n_particles, v.workgroup), push);
  }
};

}  // namespace

std::vector<Dispatch> initial_forces_program(const Model& m, const Layout& l,
                                             const KernelVariant& v, uint32_t wall_slot) {
  ProgramBuilder b;
  b.push = base_push(m, l, v);
  b.push.wall_slot = wall_slot;
  b.rebuild(l);
  gpu::SimPush frozen = b.push;
  b.push.flags |= gpu::kFlagKeepHistory;  // the setup evaluation leaves springs as they are
  b.forces(l, v);
  b.push = frozen;
  gpu::SimPush gather = b.push;
  gather.kick = 0.0f;  // forces only: F(0), T(0)
  b.direct(KernelId::GatherKick, groups(l.n_particles, v.workgroup), gather);
  return b.out;
}

std::vector<Dispatch> step_program(const Model& m, const Layout& l, const KernelVariant& v,
                                   uint32_t wall_slot) {
  ProgramBuilder b;
  b.push = base_push(m, l, v);
  b.push.wall_slot = wall_slot;
  uint32_t g = groups(l.n_particles, v.workgroup);
  if (m.integrator == Integrator::VelocityVerlet) {
    gpu::SimPush first = b.push;
    first.kick = 0.5f;
    first.flags |= gpu::kFlagDrift;
    b.direct(KernelId::KickDrift, g, first);
    b.rebuild(l);
    b.forces(l, v);
    gpu::SimPush second = b.push;
    second.kick = 0.5f;
    b.direct(KernelId::GatherKick, g, second);
  } else {
    // Symplectic Euler: forces at x(t), v(t); then v += dt a; x += dt v.
    b.rebuild(l);
    b.forces(l, v);
    gpu::SimPush last = b.push;
    last.kick = 1.0f;
    last.flags |= gpu::kFlagDrift;
    b.direct(KernelId::GatherKick, g, last);
  }
  return b.out;
}

}  // namespace repose
