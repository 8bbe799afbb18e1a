// kick_drift in SIMD lanes (kick_lanes.h): the lanes' dialect (lane_dialect.h) on
// shaders/kernels/kick.h. What is left here is memory: each particle's rows in and out, fixed
// particles (inverse mass 0) left as they are, and the skin check. Compiled once per SIMD target
// by Highway's foreach_target; -ffp-contract=off keeps every Mul and Add a separate rounding.
#include "kick_lanes.h"

#include <algorithm>
#include <cstddef>

#include "twin_kernels.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "kick_lanes.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
#include <hwy/highway.h>

#include "lane_dialect.h"  // once per target, as this file

HWY_BEFORE_NAMESPACE();
namespace repose::gpu::HWY_NAMESPACE {

// The kick's text in lanes: its functions as members.
struct LaneKick {
#include "kernels/vector3.h"
#include "kernels/kick.h"
};

// A run's rows in block order (lane_dialect.h): each lane's particle is the same slot in every row
// it loads and stores, and the kick works lane by lane.
HWY_INLINE V4 load_rows(const vec4* at) { return load4_block_order(at); }
HWY_INLINE void store_rows(vec4* at, real3 xyz, V w) { store4_block_order(at, {xyz.x.v, xyz.y.v, xyz.z.v, w}); }

// k_kick_drift for the Lanes(D()) slots from i (the kick of k_gather_kick alike: both read the
// sums stored in force and torque); true when one of them moved past half the skin.
HWY_INLINE bool kick_drift_at(Kernels& k, uint64_t i) {
  LaneKick law;
  const SimPush& pc = k.PC;
  const V4 v4 = load_rows(&k.B_vel[i]), w4 = load_rows(&k.B_omega[i]);
  const V4 force = load_rows(&k.B_force[i]), torque = load_rows(&k.B_torque[i]);
  const cond moving{hn::Ne(v4.w, hn::Zero(D()))};  // the scalar kernel leaves a fixed one alone
  const float h = pc.kick * pc.dt;
  const bool drag = pc.air_drag > 0.0f;
  real drag_area(0.0f);
  V4 p4{};
  const bool drift = (pc.flags & kFlagDrift) != 0u;
  if (drag || drift) p4 = load_rows(&k.B_pos[i]);
  if (drag) drag_area = real(pc.air_drag) * (real(p4.w) * real(p4.w));
  real3 v = law.kicked_velocity(v4.xyz(), force.xyz(), v4.w, real3(real(pc.gx), real(pc.gy), real(pc.gz)), real(h),
                                drag, drag_area);
  real3 w = law.kicked_spin(w4.xyz(), torque.xyz(), w4.w, real(h));
  v = pick(moving, v, v4.xyz());
  w = pick(moving, w, w4.xyz());
  store_rows(&k.B_vel[i], v, v4.w);
  store_rows(&k.B_omega[i], w, w4.w);
  if (!drift) return false;
  const real3 x = pick(moving, law.drifted(p4.xyz(), v, real(pc.dt)), p4.xyz());
  store_rows(&k.B_pos[i], x, p4.w);
  const V4 built = load_rows(&k.B_pos_at_build[i]);
  const real3 moved = x - built.xyz();
  const M past = hn::And(moving.m, hn::Gt(law.dot3(moved, moved).v, hn::Set(D(), pc.half_skin_sq)));
  return !hn::AllFalse(D(), past);
}

// The slots [begin, end) in runs of Lanes(D()): `sums(i, L)` for the slots of a run, then the
// run's kick (when `kick`); the tail by the scalar `kernel`. One rebuild flag for the whole range.
template <class Sums, class Kernel>
void kick_runs(Kernels& k, uint64_t begin, uint64_t end, bool kick, Sums sums, Kernel kernel) {
  const size_t L = hn::Lanes(D());
  end = std::min<uint64_t>(end, k.PC.n_particles);
  bool moved = false;
  uint64_t i = begin;
  for (; i + L <= end; i += L) {
    sums(uint(i), uint(L));
    if (kick) moved = kick_drift_at(k, i) || moved;
  }
  if (moved) atomicOr(k.B_control[kCtlNeedRebuild], 1u);
  for (; i < end; ++i) kernel(uint(i));
}

void KickDriftLanes(Kernels& k, uint64_t begin, uint64_t end) {
  kick_runs(k, begin, end, true, [](uint, uint) {}, [&](uint i) { k.k_kick_drift(i); });
}

// True when slots [i, i + n) own no entry of the list and are the partner of none: the rows'
// starts are prefix sums, so equal starts at both ends leave every row between empty.
HWY_INLINE bool no_entries(const Kernels& k, uint i, uint n) {
  const uint limit = k.B_control[kCtlContacts];
  return std::min(k.B_row_start[i], limit) == std::min(k.B_row_start[i + n], limit) &&
         k.B_trans_start[i] == k.B_trans_start[i + n];
}

// gather_contact_sums (integrate.h) for particle i: the same additions in the same order (its own
// row, then its transposed entries), each entry's three components as one 128-bit row, the load
// folded into the add (`x - F` subtracts the whole row: the w lane, summed too, is stored as 0).
// Two instructions per entry where the scalar text's three floats take six to eight: the
// gather's time is its loads at random, and fewer instructions per entry keep more of them in
// flight (docs/engineering.md). With `Ahead` each transposed entry's lines are asked for 32
// entries (~8 particles) on along the list: the row ends' mispredicted branches discard the loads
// the core had started for the next particles, but not a prefetch already on its way; `listed` is
// the transposed list's length.
constexpr uint kTransposedAhead = 32;
template <bool Ahead>
HWY_INLINE void contact_sums(Kernels& k, uint i, uint listed) {
#if HWY_TARGET == HWY_SCALAR
  vec3 f, t;
  k.gather_contact_sums(i, f, t);
#else
  const hn::FixedTag<float, 4> d4;
  const uint limit = k.B_control[kCtlContacts];
  auto fs = hn::Zero(d4), ts = hn::Zero(d4);
  const uint end = std::min(k.B_row_start[i + 1u], limit);
  for (uint c = std::min(k.B_row_start[i], limit); c < end; ++c) {
    fs = hn::Add(fs, hn::LoadU(d4, &k.B_contact_force[c].x));
    ts = hn::Add(ts, hn::LoadU(d4, &k.B_torque_i[c].x));
  }
  const uint tend = k.B_trans_start[i + 1u];
  for (uint q = k.B_trans_start[i]; q < tend; ++q) {
    const uint c = k.B_trans_list[q];
    if (Ahead && q + kTransposedAhead < listed) {
      const uint ahead = k.B_trans_list[q + kTransposedAhead];
      __builtin_prefetch(&k.B_contact_force[ahead]);
      __builtin_prefetch(&k.B_torque_j[ahead]);
    }
    fs = hn::Sub(fs, hn::LoadU(d4, &k.B_contact_force[c].x));
    ts = hn::Add(ts, hn::LoadU(d4, &k.B_torque_j[c].x));
  }
  const auto xyz = hn::FirstN(d4, 3);  // vec4(fs, 0.0f)
  hn::StoreU(hn::IfThenElseZero(xyz, fs), d4, &k.B_force[i].x);
  hn::StoreU(hn::IfThenElseZero(xyz, ts), d4, &k.B_torque[i].x);
#endif
}

// The transposed entries' prefetch pays where their lines (F and T_j, 32 B an entry) pass ~3 MB:
// LIGGGHTS's bed (6 MB) and a 50,000-sphere lattice gather 15-20 % faster, a 30,000 one (4.3 MB)
// 5 %, a 16,240 one (2.3 MB) 7 % slower, a 2,000 one in cache 15 % slower (docs/engineering.md).
constexpr uint64_t kTransposedPrefetchAboveBytes = 3u << 20;

// k_gather_kick: each particle's sums (a particle's rows differ in length, so lanes across
// particles would idle), then the kick of a run of them in lanes from the sums just stored.
void GatherKickLanes(Kernels& k, uint64_t begin, uint64_t end) {
  const uint listed = k.B_trans_start[k.PC.n_particles];
  const bool ahead = uint64_t(listed) * 2u * sizeof(vec4) > kTransposedPrefetchAboveBytes;
  auto sums = [&](uint i, uint n) {
    if (no_entries(k, i, n)) {  // a clump's inner sub-spheres: sums of nothing, +0 (gather_contact_sums)
      std::fill(k.B_force + i, k.B_force + i + n, vec4(0.0f));
      std::fill(k.B_torque + i, k.B_torque + i + n, vec4(0.0f));
      return;
    }
    if (ahead)
      for (uint l = 0; l < n; ++l) contact_sums<true>(k, i + l, listed);
    else
      for (uint l = 0; l < n; ++l) contact_sums<false>(k, i + l, listed);
  };
  kick_runs(k, begin, end, k.PC.kick > 0.0f, sums, [&](uint i) { k.k_gather_kick(i); });
}

}  // namespace repose::gpu::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace repose::gpu {

HWY_EXPORT(KickDriftLanes);
HWY_EXPORT(GatherKickLanes);

void kick_drift_lanes(Kernels& k, uint64_t begin, uint64_t end) { HWY_DYNAMIC_DISPATCH(KickDriftLanes)(k, begin, end); }
void gather_kick_lanes(Kernels& k, uint64_t begin, uint64_t end) {
  HWY_DYNAMIC_DISPATCH(GatherKickLanes)(k, begin, end);
}

}  // namespace repose::gpu
#endif
