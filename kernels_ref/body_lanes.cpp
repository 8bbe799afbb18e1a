// body_place and body_gather_kick in SIMD lanes (body_lanes.h): the lanes' dialect
// (lane_dialect.h) on shaders/kernels/rigid_body.h. What is left here is memory: the sub-spheres'
// and bodies' rows in, the placed rows and the bodies' sums out. Compiled once per SIMD target
// by Highway's foreach_target; -ffp-contract=off keeps every Mul and Add a separate rounding.
#include "body_lanes.h"

#include <algorithm>
#include <cstddef>
#include <cstring>

#include "twin_kernels.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "body_lanes.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
#include <hwy/highway.h>

#include "lane_dialect.h"  // once per target, as this file

HWY_BEFORE_NAMESPACE();
namespace repose::gpu::HWY_NAMESPACE {

// The rigid-body text in lanes: its functions as members.
struct LaneBody {
#include "kernels/vector3.h"
#include "kernels/rigid_body.h"
};

constexpr uint kSubRow = sizeof(SubSphere) / sizeof(vec4);   // vec4 rows per SubSphere
constexpr uint kMaxLanes = HWY_LANES(float);

// k_body_place for the Lanes(D()) slots from i, in block order (lane l slot i + block_order(l),
// lane_dialect.h); true when one of them moved past half the skin.
bool place_lanes(Kernels& k, uint64_t i) {
  const size_t L = hn::Lanes(D());
  LaneBody law;
  uint body[kMaxLanes], at[kMaxLanes];
  bool one_body = true;
  for (size_t l = 0; l < L; ++l) {
    const uint64_t slot = i + block_order(l);
    body[l] = k.B_subs[slot].info.x;
    at[l] = uint(slot * kSubRow);
    one_body = one_body && body[l] == body[0];
  }
  V4 local = rows(reinterpret_cast<const vec4*>(k.B_subs), at);
  V4 p4, vel, quat, omega;
  if (one_body) {  // cell order keeps a body's sub-spheres in a run of slots: the usual case
    const Body& b = k.B_bodies[body[0]];
    p4 = same_row(b.pos), vel = same_row(b.vel), quat = same_row(b.quat), omega = same_row(b.omega);
  } else {
    p4 = body_rows(k, body, offsetof(Body, pos) / sizeof(vec4));
    vel = body_rows(k, body, offsetof(Body, vel) / sizeof(vec4));
    quat = body_rows(k, body, offsetof(Body, quat) / sizeof(vec4));
    omega = body_rows(k, body, offsetof(Body, omega) / sizeof(vec4));
  }
  real3 r, x, v;
  law.place_sub(p4.xyz(), vel.xyz(), omega.xyz(), quat.xyz(), quat.w, local.xyz(), r, x, v);
  store4_block_order(&k.B_pos[i], {x.x.v, x.y.v, x.z.v, local.w});
  store4_block_order(&k.B_vel[i], {v.x.v, v.y.v, v.z.v, p4.w});
  store4_block_order(&k.B_omega[i], {omega.x, omega.y, omega.z, hn::Zero(D())});
  if ((k.PC.flags & kFlagDrift) == 0u) return false;
  const V4 built = load4_block_order(&k.B_pos_at_build[i]);
  real3 moved = x - built.xyz();
  return !hn::AllFalse(D(), hn::Gt(law.dot3(moved, moved).v, hn::Set(D(), k.PC.half_skin_sq)));
}

void PlaceLanes(Kernels& k, uint64_t begin, uint64_t end) {
  const size_t L = hn::Lanes(D());
  end = std::min<uint64_t>(end, k.PC.n_particles);
  bool moved = false;
  uint64_t i = begin;
  for (; i + L <= end; i += L) moved = place_lanes(k, i) || moved;
  if (moved) atomicOr(k.B_control[kCtlNeedRebuild], 1u);
  for (; i < end; ++i) k.k_body_place(uint(i));
}

// Sub-spheres whose rows (force, torque, SubSphere: 64 B each) outgrow this: gather_lanes asks
// for each lane's lines ahead. Sixteen lanes read sixteen bodies' rows, each a stream of its own,
// more than the hardware prefetcher follows; in cell order a body's sub-spheres sit in a run of
// slots, so the lines a few sub-spheres on are the next ones. The cotton bucket with the study's
// 720-sphere stalk (326,880 sub-spheres, 21 MB) gains; the cabbage heaps (1 MB) sit in the caches,
// where asking only costs instructions (docs/engineering.md).
constexpr uint64_t kPrefetchAboveBytes = 8u << 20;

HWY_INLINE void prefetch_ahead(const Kernels& k, const uint* slot) {
  for (size_t l = 0; l < hn::Lanes(D()); ++l) {
    __builtin_prefetch(&k.B_force[slot[l] + 8]);  // 8 rows on: two lines ahead
    __builtin_prefetch(&k.B_torque[slot[l] + 8]);
    __builtin_prefetch(&k.B_subs[slot[l] + 8]);  // a SubSphere is half a line: four take two
    __builtin_prefetch(&k.B_subs[slot[l] + 10]);
  }
}

// k_body_gather_kick for the Lanes(D()) bodies from b0: lane l sums body b0 + l's sub-spheres in
// their order (a lane whose body has fewer keeps its sums), then each body kicks on its own.
void gather_lanes(Kernels& k, uint64_t b0, bool ahead) {
  const size_t L = hn::Lanes(D());
  LaneBody law;
  uint first[kMaxLanes], count[kMaxLanes], body[kMaxLanes], most = 0;
  for (size_t l = 0; l < L; ++l) {
    body[l] = uint(b0 + l);
    first[l] = k.B_bodies[body[l]].spheres.x;
    count[l] = k.B_bodies[body[l]].spheres.y;
    most = std::max(most, count[l]);
  }
  V4 quat = body_rows(k, body, offsetof(Body, quat) / sizeof(vec4));
  const DI di;
  const VI counts = hn::LoadU(di, reinterpret_cast<const int32_t*>(count));
  real3 f(0.0f), t(0.0f);
  uint slot[kMaxLanes], sub_row[kMaxLanes];
  for (uint m = 0; m < most; ++m) {
    for (size_t l = 0; l < L; ++l) {
      slot[l] = k.slot_of(first[l] + std::min(m, count[l] - 1u));
      sub_row[l] = slot[l] * kSubRow;
    }
    if (ahead && (m & 3u) == 0u) prefetch_ahead(k, slot);  // a line holds four rows
    V4 fs = rows(k.B_force, slot), ts = rows(k.B_torque, slot);
    V4 local = rows(reinterpret_cast<const vec4*>(k.B_subs), sub_row);
    real3 r = law.rotate_by(quat.xyz(), quat.w, local.xyz());
    real3 f1 = f, t1 = t;
    law.add_sub_force(f1, t1, r, fs.xyz(), ts.xyz());
    cond active{hn::RebindMask(D(), hn::Lt(hn::Set(di, int32_t(m)), counts))};
    f = pick(active, f1, f);
    t = pick(active, t1, t);
  }
  float sums[6][kMaxLanes];
  const real* parts[6] = {&f.x, &f.y, &f.z, &t.x, &t.y, &t.z};
  for (int c = 0; c < 6; ++c) hn::StoreU(parts[c]->v, D(), sums[c]);
  for (size_t l = 0; l < L; ++l) {
    vec3 fb(sums[0][l], sums[1][l], sums[2][l]), tb(sums[3][l], sums[4][l], sums[5][l]);
    k.B_bodies[body[l]].force = vec4(fb, 0.0f);
    k.B_bodies[body[l]].torque = vec4(tb, 0.0f);
    if (k.PC.kick > 0.0f) k.body_kick_and_drift(body[l], fb, tb);
  }
}

void GatherLanes(Kernels& k, uint64_t begin, uint64_t end) {
  const size_t L = hn::Lanes(D());
  end = std::min<uint64_t>(end, k.PC.n_bodies);
  uint64_t b = begin;
  const bool ahead = uint64_t(k.PC.n_particles) * (2 * sizeof(vec4) + sizeof(SubSphere)) > kPrefetchAboveBytes;
  for (; b + L <= end; b += L) gather_lanes(k, b, ahead);
  for (; b < end; ++b) k.k_body_gather_kick(uint(b));
}

}  // namespace repose::gpu::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace repose::gpu {

HWY_EXPORT(PlaceLanes);
HWY_EXPORT(GatherLanes);

void body_place_lanes(Kernels& k, uint64_t begin, uint64_t end) { HWY_DYNAMIC_DISPATCH(PlaceLanes)(k, begin, end); }
void body_gather_kick_lanes(Kernels& k, uint64_t begin, uint64_t end) {
  HWY_DYNAMIC_DISPATCH(GatherLanes)(k, begin, end);
}

}  // namespace repose::gpu
#endif
