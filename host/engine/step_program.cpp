#include "engine/step_program.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "util/env_setting.h"

namespace repose {

std::string KernelVariant::name() const {
  std::string s = contact == ContactKernel::PerContact ? "contact" : "rows";
  s += "-wg" + std::to_string(workgroup);
  if (rebuild_interval) s += "-every" + std::to_string(rebuild_interval);
  if (lean) s += "-lean";
  if (reorder != kDefaultReorder || !reorder_capped) s += "-reorder" + std::to_string(reorder);
  return s;
}

namespace {

// The number after "wg=" or "rebuild=": digits only, at most a million.
uint32_t whole(const std::string& item, size_t from) {
  std::string digits = item.substr(from);
  if (digits.empty() || digits.size() > 7 || digits.find_first_not_of("0123456789") != std::string::npos)
    throw std::invalid_argument("'" + item + "': expected a whole number after '='");
  return uint32_t(std::stoul(digits));
}

}  // namespace

KernelVariant KernelVariant::parse(const std::string& text) {
  KernelVariant v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item.empty()) continue;
    if (item == "contact") v.contact = ContactKernel::PerContact;
    else if (item == "rows") v.contact = ContactKernel::PerRow;
    else if (item == "lean") v.lean = true;
    else if (item == "full") v.lean = false;
    else if (item.rfind("wg=", 0) == 0) v.workgroup = whole(item, 3);
    else if (item.rfind("rebuild=", 0) == 0) v.rebuild_interval = whole(item, 8);
    else if (item.rfind("reorder=", 0) == 0) {
      v.reorder = whole(item, 8);
      v.reorder_capped = false;
    }
    else throw std::invalid_argument("unknown variant item '" + item +
                                     "' (contact, rows, lean, full, wg=N, rebuild=N, reorder=N)");
  }
  if (v.workgroup == 0 || v.workgroup > 1024 || (v.workgroup & (v.workgroup - 1)))
    throw std::invalid_argument("wg must be a power of two up to 1024");
  return v;
}

KernelVariant KernelVariant::fastest_for(const std::string& backend, const Model& m) {
  KernelVariant v;
  v.lean = backend == "vulkan" && (m.flags & gpu::kFlagsNeedFullEntries) == 0u;
  return v;
}

Layout model_layout(const Model& m, const KernelVariant& v, uint32_t batch_steps, uint32_t capacity) {
  if ((m.flags & gpu::kFlagsNeedFullEntries) != 0u && v.lean) {
    const char* option = (m.flags & gpu::kFlagRollingSpring) ? "rolling = \"epsd\" stores each contact's rolling torque"
                                                              : "spinning_friction stores each contact's torques";
    throw std::invalid_argument(std::string(option) + ": use the 'full' kernel variant, not 'lean'");
  }
  Layout l;
  l.n_particles = m.n_particles;
  l.n_walls = static_cast<uint32_t>(m.walls.size());
  l.n_moving_walls = static_cast<uint32_t>(m.moving_walls.size());
  l.n_wall_groups = m.n_wall_groups;
  l.wall_grid_words = static_cast<uint32_t>(m.wall_grid.size());
  l.n_materials = m.n_materials;
  l.table_size = m.table_size;
  l.batch_steps = std::max<uint32_t>(1, batch_steps);
  l.lean_contacts = v.lean;
  l.rolling_springs = (m.flags & gpu::kFlagRollingSpring) != 0;
  l.n_bodies = static_cast<uint32_t>(m.bodies.size());
  l.n_parts = static_cast<uint32_t>(m.parts.size());
  l.capacity = capacity;
  return l;
}

gpu::SimPush base_push(const Model& m, const Layout& l, const KernelVariant& v, bool walls_still) {
  gpu::SimPush p{};
  p.n_particles = l.n_particles;
  p.n_walls = l.n_walls;
  p.n_moving_walls = l.n_moving_walls;
  p.n_wall_groups = l.n_wall_groups;
  p.wall_table_size = l.wall_grid_words ? m.wall_table_size : 0u;
  p.capacity = l.capacity;
  p.table_size = l.table_size;
  p.n_materials = l.n_materials;
  p.flags = m.flags | (v.lean ? gpu::kFlagLeanContacts : 0u) |
            (l.n_bodies ? gpu::kFlagBodies : 0u);
  p.n_bodies = l.n_bodies;
  p.n_parts = l.n_parts;
  p.wall_slot = 0;
  uint32_t interval = walls_still ? m.still_interval : m.max_interval;
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
  p.large_radius = float(m.large_radius);
  p.air_drag = float(m.air_drag);
  p.rolling_damping = float(m.rolling_damping);
  p.max_groups_x = max_groups_x();
  p.absent_wall_kinds = 0xFu;
  for (const ModelWall& w : m.walls) p.absent_wall_kinds &= ~(1u << w.kind);
  return p;
}

uint32_t max_groups_x() {
  static const uint32_t limit = uint32_t(env_whole_number("REPOSE_MAX_GROUPS_X", gpu::kMaxGroupsX, gpu::kMaxGroupsX));
  return limit;
}

uint32_t scan_blocks_from() {
  static const uint32_t from = uint32_t(env_whole_number("REPOSE_SCAN_BLOCKS_FROM", kScanBlocksFrom, 0xffffffffu));
  return from;
}

bool scan_in_blocks(uint32_t count) { return gpu::scan_blocks_for(count) >= scan_blocks_from(); }

std::vector<Dispatch> scan_dispatches(uint32_t target, uint32_t count, bool in_blocks) {
  Dispatch d;
  d.kernel = KernelId::Scan;
  d.indirect_word = gpu::kCtlArgsOne;
  d.scan = {target, count, gpu::kScanPassWhole};
  if (!in_blocks) return {d};
  uint32_t blocks_word = target == gpu::kScanCells ? gpu::kCtlArgsScanBuckets : gpu::kCtlArgsScanParticles;
  std::vector<Dispatch> passes(3, d);
  passes[0].indirect_word = passes[2].indirect_word = static_cast<int32_t>(blocks_word);
  passes[0].scan.pass = gpu::kScanPassSums;
  passes[1].scan.pass = gpu::kScanPassOffsets;
  passes[2].scan.pass = gpu::kScanPassBlocks;
  return passes;
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
    std::vector<Dispatch> passes = scan_dispatches(target, count, scan_in_blocks(count));
    out.insert(out.end(), passes.begin(), passes.end());
  }
  // Rebuilds the contact list when rebuild_args decides so (indirect sizes are 0 otherwise).
  void rebuild(const Layout& l) {
    direct(KernelId::RebuildArgs, 1, push);
    if (push.flags & gpu::kFlagBodyBroadPhase) {  // before the buckets: they leave out what meets no other body
      indirect(KernelId::PartPlace, gpu::kCtlArgsParts);
      indirect(KernelId::PartNear, gpu::kCtlArgsBodies);
    }
    indirect(KernelId::SaveOldRows, gpu::kCtlArgsParticles);
    indirect(KernelId::SaveOldContacts, gpu::kCtlArgsOldContacts);
    indirect(KernelId::ClearBuckets, gpu::kCtlArgsBuckets);
    indirect(KernelId::BucketCount, gpu::kCtlArgsParticles);
    scan(gpu::kScanCells, l.table_size + 1);  // the hashed buckets and the large one
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
    if (push.flags & gpu::kFlagSpinningFriction) {  // its limiter counts each body's touching contacts
      direct(KernelId::ClearTouches, groups(l.n_particles, v.workgroup), push);
      indirect(KernelId::TouchCount, gpu::kCtlArgsContacts);
    }
    if (v.contact == ContactKernel::PerContact)
      indirect(KernelId::ContactForces, gpu::kCtlArgsContacts);
    else
      direct(KernelId::ContactRows, groups(l.n_particles, v.workgroup), push);
  }
  // Sums the contacts into F, T and applies `kick` (with the push's drift flag). The lean
  // gather with the relative rolling torque reads other particles' spins, so there the kick
  // is a pass of its own (the same arithmetic, F and T read back as stored). With bodies the
  // particles only sum; their bodies sum them and move, and a drift re-places the particles.
  void gather(const Layout& l, const KernelVariant& v, const gpu::SimPush& p) {
    uint32_t g = groups(l.n_particles, v.workgroup);
    if (l.n_bodies) {
      gpu::SimPush sum_only = p;
      sum_only.kick = 0.0f;
      sum_only.flags &= ~gpu::kFlagDrift;
      direct(v.lean ? KernelId::GatherLean : KernelId::GatherKick, g, sum_only);
      direct(KernelId::BodyGatherKick, groups(l.n_bodies, v.workgroup), p);
      if (p.flags & gpu::kFlagDrift) direct(KernelId::BodyPlace, g, p);
    } else if (!v.lean) {
      direct(KernelId::GatherKick, g, p);
    } else if ((p.flags & gpu::kFlagRollingRelativeOmega) && p.kick > 0.0f) {
      gpu::SimPush only = p;
      only.kick = 0.0f;
      direct(KernelId::GatherLean, g, only);
      direct(KernelId::KickDrift, g, p);
    } else {
      direct(KernelId::GatherLean, g, p);
    }
  }
};

}  // namespace

std::vector<Dispatch> body_place_program(const Model& m, const Layout& l, const KernelVariant& v) {
  ProgramBuilder b;
  b.push = base_push(m, l, v);
  if (l.n_bodies) b.direct(KernelId::BodyPlace, groups(l.n_particles, v.workgroup), b.push);
  return b.out;
}

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
  b.gather(l, v, gather);
  return b.out;
}

std::vector<Dispatch> step_program(const Model& m, const Layout& l, const KernelVariant& v,
                                   uint32_t wall_slot, bool walls_still) {
  ProgramBuilder b;
  b.push = base_push(m, l, v, walls_still);
  b.push.wall_slot = wall_slot;
  uint32_t g = groups(l.n_particles, v.workgroup);
  if (m.integrator == Integrator::VelocityVerlet) {
    gpu::SimPush first = b.push;
    first.kick = 0.5f;
    first.flags |= gpu::kFlagDrift;
    if (l.n_bodies) {
      b.direct(KernelId::BodyKickDrift, groups(l.n_bodies, v.workgroup), first);
      b.direct(KernelId::BodyPlace, g, first);
    } else {
      b.direct(KernelId::KickDrift, g, first);
    }
    b.rebuild(l);
    b.forces(l, v);
    gpu::SimPush second = b.push;
    second.kick = 0.5f;
    b.gather(l, v, second);
  } else {
    // Symplectic Euler: forces at x(t), v(t); then v += dt a; x += dt v.
    b.rebuild(l);
    b.forces(l, v);
    gpu::SimPush last = b.push;
    last.kick = 1.0f;
    last.flags |= gpu::kFlagDrift;
    b.gather(l, v, last);
  }
  return b.out;
}

}  // namespace repose
