// process_contact in SIMD lanes (contact_lanes.h). Every function below mirrors the kernel
// function of the same name in shaders/kernels/, operation for operation: a change there must be
// made here too, and test_contact_lanes.cpp fails until it is. Compiled once per SIMD target by
// Highway's foreach_target; -ffp-contract=off keeps every Mul and Add a separate rounding.
#include "contact_lanes.h"

#include <atomic>
#include <cstddef>
#include <cstring>

#include "twin_kernels.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "contact_lanes.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace repose::gpu::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<D>;
using V = hn::Vec<D>;
using VI = hn::Vec<DI>;
using M = hn::Mask<D>;

struct V3 {
  V x, y, z;
};

// common.h, one lane per contact.
V3 add3(V3 a, V3 b) { return {hn::Add(a.x, b.x), hn::Add(a.y, b.y), hn::Add(a.z, b.z)}; }
V3 sub3(V3 a, V3 b) { return {hn::Sub(a.x, b.x), hn::Sub(a.y, b.y), hn::Sub(a.z, b.z)}; }
V3 scale3(V3 a, V s) { return {hn::Mul(a.x, s), hn::Mul(a.y, s), hn::Mul(a.z, s)}; }
V dot3(V3 a, V3 b) { return hn::Add(hn::Add(hn::Mul(a.x, b.x), hn::Mul(a.y, b.y)), hn::Mul(a.z, b.z)); }
V length3(V3 a) { return hn::Sqrt(dot3(a, a)); }
V3 cross3(V3 a, V3 b) {
  return {hn::Sub(hn::Mul(a.y, b.z), hn::Mul(a.z, b.y)), hn::Sub(hn::Mul(a.z, b.x), hn::Mul(a.x, b.z)),
          hn::Sub(hn::Mul(a.x, b.y), hn::Mul(a.y, b.x))};
}
V3 select3(M m, V3 yes, V3 no) {
  return {hn::IfThenElse(m, yes.x, no.x), hn::IfThenElse(m, yes.y, no.y), hn::IfThenElse(m, yes.z, no.z)};
}
V3 zero_unless(M m, V3 a) { return {hn::IfThenElseZero(m, a.x), hn::IfThenElseZero(m, a.y), hn::IfThenElseZero(m, a.z)}; }
V vset(float f) { return hn::Set(D(), f); }
// std::max(a, b) exactly: a < b ? b : a (which operand wins on equal zeros and NaN).
V max_of(V a, V b) { return hn::IfThenElse(hn::Lt(a, b), b, a); }

// Field `word` of the structs at indices `index`, each `stride` 4-byte words long.
V gather(const void* base, VI index, int stride, int word) {
  VI at = hn::Add(hn::Mul(index, hn::Set(DI(), stride)), hn::Set(DI(), word));
  return hn::GatherIndex(D(), static_cast<const float*>(base), at);
}
VI gather_int(const void* base, VI index, int stride, int word) {
  VI at = hn::Add(hn::Mul(index, hn::Set(DI(), stride)), hn::Set(DI(), word));
  return hn::GatherIndex(DI(), static_cast<const int32_t*>(base), at);
}

// What one lane holds of a contact: contacts.h's ContactState and ContactGeometry.
struct Lanes {
  M touching;
  V3 n, v_rel, wi, wj;
  V overlap, dist, radius_star, mass_star, ri, rj, lever_i, lever_j, cohesion_lens;
};

// The per-pair parameters of each lane: every row of REPOSE_PAIR_PARAMS (repose_shared.h), by name.
struct Params {
#define REPOSE_LANE_PARAM(name, unit, source) V name;
  REPOSE_PAIR_PARAMS(REPOSE_LANE_PARAM)
#undef REPOSE_LANE_PARAM
};

Params gather_params(Kernels& k, VI mi, VI mj) {
  const PairParams* pairs = k.B_pairs;
  VI pair = hn::Add(hn::Mul(mi, hn::Set(DI(), int(k.PC.n_materials))), mj);
  int32_t first = hn::GetLane(pair);
  Params out;
  if (hn::AllTrue(DI(), hn::Eq(pair, hn::Set(DI(), first)))) {  // one pair (the usual case): no gathers
    const PairParams& p = pairs[first];
#define REPOSE_LANE_PARAM_SET(name, unit, source) out.name = vset(p.name);
    REPOSE_PAIR_PARAMS(REPOSE_LANE_PARAM_SET)
#undef REPOSE_LANE_PARAM_SET
    return out;
  }
  constexpr int W = sizeof(PairParams) / 4;
#define REPOSE_LANE_PARAM_GATHER(name, unit, source) out.name = gather(pairs, pair, W, offsetof(PairParams, name) / 4);
  REPOSE_PAIR_PARAMS(REPOSE_LANE_PARAM_GATHER)
#undef REPOSE_LANE_PARAM_GATHER
  return out;
}

// integrate.h rolling_lever.
V rolling_lever(Kernels& k, VI sphere, V3 cp, V r) {
  constexpr int SW = sizeof(SubSphere) / 4, BW = sizeof(Body) / 4;
  constexpr int info_x = offsetof(SubSphere, info) / 4, count = offsetof(Body, spheres) / 4 + 1;
  VI b = gather_int(k.B_subs, sphere, SW, info_x);
  M lone = hn::RebindMask(D(), hn::Lt(gather_int(k.B_bodies, b, BW, count), hn::Set(DI(), 2)));
  V3 centre = {gather(k.B_bodies, b, BW, 0), gather(k.B_bodies, b, BW, 1), gather(k.B_bodies, b, BW, 2)};
  return hn::IfThenElse(lone, r, length3(sub3(cp, centre)));
}

// contacts.h cohesion_lens and contact_law.h cohesion_intersection_area (two spheres).
V cohesion_lens(Kernels& k, V r1, V r2, V dist, V overlap) {
  if ((k.PC.flags & kFlagCohesionIntersection) == 0u) return vset(-1.0f);
  V q = hn::Mul(hn::Mul(hn::Mul(overlap, hn::Sub(hn::Add(dist, r1), r2)), hn::Add(hn::Sub(dist, r1), r2)),
                hn::Add(hn::Add(dist, r1), r2));
  return hn::Div(q, hn::Mul(hn::Mul(vset(4.0f), dist), dist));
}

// The vec4 rows base[index[l]] of the lanes, as four vectors (x, y, z, w). One 16-byte copy per
// lane and one transpose: a gather per component costs several times more.
struct V4 {
  V x, y, z, w;
  V3 xyz() const { return {x, y, z}; }
};
V4 rows(const vec4* base, const uint* index) {
  alignas(64) float buf[4 * HWY_LANES(float)];
  const size_t L = hn::Lanes(D());
  for (size_t l = 0; l < L; ++l) std::memcpy(buf + 4 * l, base + index[l], sizeof(vec4));
  V4 r;
  hn::LoadInterleaved4(D(), buf, r.x, r.y, r.z, r.w);
  return r;
}

// contacts.h touch_particle (and set_rolling_levers) for the lanes of owners i and partners p
// (the same as vectors i_, p_ for the body gathers).
Lanes touch_particle(Kernels& k, const uint* i, const uint* p, VI i_, VI p_) {
  Lanes s;
  V4 pos_i = rows(k.B_pos, i), pos_j = rows(k.B_pos, p);
  V4 vel_i = rows(k.B_vel, i), vel_j = rows(k.B_vel, p);
  V3 xi = pos_i.xyz(), xj = pos_j.xyz(), vi = vel_i.xyz(), vj = vel_j.xyz();
  V rad_i = pos_i.w, rad_j = pos_j.w, inv_mi = vel_i.w, inv_mj = vel_j.w;
  s.wi = rows(k.B_omega, i).xyz();
  s.wj = rows(k.B_omega, p).xyz();
  V3 d = sub3(xi, xj);
  s.dist = length3(d);
  s.overlap = hn::Sub(hn::Add(rad_i, rad_j), s.dist);
  V zero = hn::Zero(D());
  s.touching = hn::And(hn::Gt(s.overlap, zero), hn::Gt(s.dist, zero));
  s.n = {hn::Div(d.x, s.dist), hn::Div(d.y, s.dist), hn::Div(d.z, s.dist)};
  s.radius_star = hn::Div(hn::Mul(rad_i, rad_j), hn::Add(rad_i, rad_j));
  s.mass_star = hn::Div(vset(1.0f), hn::Add(inv_mi, inv_mj));
  V half_overlap = hn::Mul(vset(0.5f), s.overlap);
  s.ri = hn::Sub(rad_i, half_overlap);
  s.rj = hn::Sub(rad_j, half_overlap);
  V3 spin = add3(scale3(s.wi, s.ri), scale3(s.wj, s.rj));
  s.v_rel = sub3(sub3(vi, vj), cross3(spin, s.n));
  s.cohesion_lens = cohesion_lens(k, rad_i, rad_j, s.dist, s.overlap);
  s.lever_i = s.ri;
  s.lever_j = s.rj;
  if (k.centre_lever(k.PC.flags) && (k.PC.flags & kFlagLeanContacts) == 0u) {
    V3 cp = sub3(xi, scale3(s.n, s.ri));  // contact_point
    s.lever_i = rolling_lever(k, i_, cp, s.ri);
    s.lever_j = rolling_lever(k, p_, cp, s.rj);
  }
  return s;
}

// contact_law.h turn_into_tangent_plane.
V3 turn_into_tangent_plane(V3 s, V3 n) {
  V old_sq = dot3(s, s);
  V3 p = sub3(s, scale3(n, dot3(s, n)));
  V new_sq = dot3(p, p);
  M turn = hn::Gt(new_sq, hn::Zero(D()));
  return select3(turn, scale3(p, hn::Sqrt(hn::Div(old_sq, new_sq))), p);
}

// contact_law.h body_torque.
V3 body_torque(V3 n_x_ft, V r, V roll_arm, V lever, V3 w, V lw) {
  V3 t = scale3(n_x_ft, hn::Neg(r));
  V zero = hn::Zero(D());
  M rolls = hn::And(hn::Ge(roll_arm, zero), hn::Gt(lw, zero));
  V kk = hn::Neg(hn::Div(hn::Mul(roll_arm, lever), lw));
  return select3(rolls, add3(t, scale3(w, kk)), t);
}

// What hertz_mindlin returns that the stores need.
struct Out {
  V3 force_i, torque_i, torque_j, n_x_ft, shear;
  V normal_force, roll_arm;
};

// contact_law.h contact_torques for two particles.
void contact_torques(const Lanes& g, uint flags, Out& o) {
  bool relative = (flags & kFlagRollingRelativeOmega) != 0u;
  V zero = hn::Zero(D());
  V arm = o.roll_arm;
  V own_arm = relative ? vset(-1.0f) : arm;
  M own = hn::Ge(own_arm, zero);
  V lw_i = hn::IfThenElseZero(own, length3(g.wi));
  V lw_j = hn::IfThenElseZero(own, length3(g.wj));
  o.torque_i = body_torque(o.n_x_ft, g.ri, own_arm, g.lever_i, g.wi, lw_i);
  o.torque_j = body_torque(o.n_x_ft, g.rj, own_arm, g.lever_j, g.wj, lw_j);
  if (!relative) return;
  // relative_rolling with lever R*.
  V3 w = sub3(g.wi, g.wj);
  V lw = length3(w);
  M rolls = hn::And(hn::Ge(arm, zero), hn::Gt(lw, zero));
  V kk = hn::Neg(hn::Div(hn::Mul(arm, g.radius_star), lw));
  V3 t = scale3(w, kk);
  V3 tr = sub3(t, scale3(g.n, dot3(t, g.n)));
  o.torque_i = select3(rolls, add3(o.torque_i, tr), o.torque_i);
  o.torque_j = select3(rolls, sub3(o.torque_j, tr), o.torque_j);
}

// contact_law.h hertz_mindlin for two particles.
Out hertz_mindlin(const Lanes& g, const Params& pp, float dt, uint flags, V3 shear) {
  Out o;
  V zero = hn::Zero(D());
  V sqrt_rd = hn::Sqrt(hn::Mul(g.radius_star, g.overlap));
  V sn = hn::Mul(hn::Mul(vset(2.0f), pp.e_star), sqrt_rd);
  V st = hn::Mul(hn::Mul(vset(8.0f), pp.g_star), sqrt_rd);
  V fn_elastic = hn::Div(hn::Mul(hn::Mul(hn::Mul(vset(4.0f), pp.e_star), sqrt_rd), g.overlap), vset(3.0f));
  V gamma_n = hn::Mul(pp.damping, hn::Sqrt(hn::Mul(sn, g.mass_star)));
  V gamma_t = hn::Mul(pp.damping, hn::Sqrt(hn::Mul(st, g.mass_star)));

  V vn = dot3(g.v_rel, g.n);
  V3 v_t = sub3(g.v_rel, scale3(g.n, vn));

  V fn = hn::Sub(fn_elastic, hn::Mul(gamma_n, vn));
  // viscoelastic_damping
  fn = hn::Sub(fn, hn::IfThenElseZero(hn::Gt(pp.viscoelastic_time, zero), hn::Mul(hn::Mul(pp.viscoelastic_time, sn), vn)));
  if ((flags & kFlagClipAttraction) != 0u) fn = max_of(fn, zero);
  V fn_grip = fn;
  // linear_cohesion
  V lens_force = hn::Mul(pp.cohesion_pi_k, g.cohesion_lens);
  V hertz_force = hn::Mul(hn::Mul(pp.cohesion_pi_k, g.radius_star), g.overlap);
  V cohesion = hn::IfThenElse(hn::Ge(g.cohesion_lens, zero), lens_force, hertz_force);
  fn = hn::Sub(fn, hn::IfThenElseZero(hn::Gt(pp.cohesion_pi_k, zero), cohesion));
  if ((flags & kFlagCohesionContactFriction) == 0u) fn_grip = fn;

  V3 spring = add3(turn_into_tangent_plane(shear, g.n), scale3(v_t, vset(dt)));
  V3 f_spring = scale3(spring, hn::Neg(st));
  V3 f_damp = scale3(v_t, hn::Neg(gamma_t));
  V ft_max = hn::Mul(pp.static_friction, hn::Abs(fn_grip));
  V3 ft;
  if ((flags & kFlagCoulombSpringOnly) != 0u) {
    V fs = length3(f_spring);
    M slips = hn::Gt(fs, ft_max);
    V3 capped = scale3(spring, hn::Div(ft_max, fs));
    ft = select3(slips, scale3(capped, hn::Neg(st)), add3(f_spring, f_damp));
    spring = select3(slips, capped, spring);
  } else {
    ft = add3(f_spring, f_damp);
    V f = length3(ft);
    M slips = hn::Gt(f, ft_max);
    V3 capped = scale3(ft, hn::Div(ft_max, f));
    V inv_st = hn::Div(vset(-1.0f), st);
    ft = select3(slips, capped, ft);
    spring = select3(slips, scale3(capped, inv_st), spring);
  }
  o.shear = spring;
  o.n_x_ft = cross3(g.n, ft);
  o.force_i = add3(scale3(g.n, fn), ft);
  o.normal_force = fn;
  bool relative = (flags & kFlagRollingRelativeOmega) != 0u;
  V roll_force = relative ? fn_elastic : hn::Abs(fn_grip);
  M rolling = hn::Gt(pp.rolling_friction, zero);
  if ((flags & kFlagRollingConstTorque) == 0u) rolling = hn::Lt(zero, zero);
  o.roll_arm = hn::IfThenElse(rolling, hn::Mul(pp.rolling_friction, roll_force), vset(-1.0f));
  if ((flags & kFlagLeanContacts) == 0u) contact_torques(g, flags, o);
  return o;
}

void store4(vec4* at, V x, V y, V z, V w) { hn::StoreInterleaved4(x, y, z, w, D(), &at->x); }

// process_contact for the Lanes(D()) contacts from c between particles i and p.
void particle_lanes(Kernels& k, uint64_t c, const uint* i_at, const uint* p_at) {
  const DI di;
  VI i = hn::LoadU(di, reinterpret_cast<const int32_t*>(i_at));
  VI p = hn::LoadU(di, reinterpret_cast<const int32_t*>(p_at));
  const uint flags = k.PC.flags;
  Lanes s = touch_particle(k, i_at, p_at, i, p);
  V hx, hy, hz, hw;
  hn::LoadInterleaved4(D(), &k.B_history[c].x, hx, hy, hz, hw);
  VI mi = hn::GatherIndex(DI(), reinterpret_cast<const int32_t*>(k.B_material), i);
  VI mj = hn::GatherIndex(DI(), reinterpret_cast<const int32_t*>(k.B_material), p);
  Out o = hertz_mindlin(s, gather_params(k, mi, mj), k.PC.dt, flags, V3{hx, hy, hz});
  M t = s.touching;
  if ((flags & kFlagKeepHistory) == 0u) {
    V age = hn::Add(hw, vset(1.0f));
    store4(&k.B_history[c], hn::IfThenElseZero(t, o.shear.x), hn::IfThenElseZero(t, o.shear.y),
           hn::IfThenElseZero(t, o.shear.z), hn::IfThenElseZero(t, age));
  } else {
    store4(&k.B_history[c], hn::IfThenElseZero(t, hx), hn::IfThenElseZero(t, hy), hn::IfThenElseZero(t, hz),
           hn::IfThenElseZero(t, hw));
  }
  V3 f = zero_unless(t, o.force_i);
  V zero = hn::Zero(D());
  if ((flags & kFlagLeanContacts) != 0u) {
    V3 nf = zero_unless(t, o.n_x_ft);
    store4(&k.B_contact_force[c], f.x, f.y, f.z, hn::IfThenElseZero(t, o.roll_arm));
    store4(&k.B_torque_i[c], nf.x, nf.y, nf.z, hn::IfThenElseZero(t, s.overlap));
    return;
  }
  V3 ti = zero_unless(t, o.torque_i), tj = zero_unless(t, o.torque_j);
  store4(&k.B_contact_force[c], f.x, f.y, f.z, hn::IfThenElseZero(t, o.normal_force));
  store4(&k.B_torque_i[c], ti.x, ti.y, ti.z, zero);
  store4(&k.B_torque_j[c], tj.x, tj.y, tj.z, zero);
}

// Lanes whose partner is a wall (walls sort last in a row) run in the lanes as a contact of the
// owner with itself (centres coincide: not touching), with their history kept aside; then the
// scalar kernel computes them from that history.
void mixed_lanes(Kernels& k, uint64_t c) {
  const size_t L = hn::Lanes(D());
  uint partner[HWY_LANES(float)];
  vec4 history[HWY_LANES(float)];
  for (size_t l = 0; l < L; ++l) {
    bool wall = k.B_partner[c + l] >= k.PC.n_particles;
    partner[l] = wall ? k.B_owner[c + l] : k.B_partner[c + l];
    history[l] = k.B_history[c + l];
  }
  particle_lanes(k, c, k.B_owner + c, partner);
  for (size_t l = 0; l < L; ++l) {
    if (partner[l] == k.B_partner[c + l]) continue;
    k.B_history[c + l] = history[l];
    k.process_contact(k.B_owner[c + l], uint(c + l));
  }
}

void ContactLanes(Kernels& k, uint64_t begin, uint64_t end) {
  const DI di;
  const size_t L = hn::Lanes(di);
  const VI particles = hn::Set(di, int32_t(k.PC.n_particles));
  uint64_t c = begin;
  for (; c + L <= end; c += L) {
    VI p = hn::LoadU(di, reinterpret_cast<const int32_t*>(k.B_partner + c));
    if (hn::AllTrue(di, hn::Lt(p, particles)))
      particle_lanes(k, c, k.B_owner + c, k.B_partner + c);
    else
      mixed_lanes(k, c);
  }
  for (; c < end; ++c) k.process_contact(k.B_owner[c], uint(c));
}

const char* LanesTarget() { return hwy::TargetName(HWY_TARGET); }

}  // namespace repose::gpu::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace repose::gpu {

HWY_EXPORT(ContactLanes);
HWY_EXPORT(LanesTarget);

namespace {
std::atomic<bool> g_lanes_on{true};
}

bool contact_lanes_cover(uint flags) {
  return g_lanes_on.load(std::memory_order_relaxed) &&
         (flags & (kFlagRollingSpring | kFlagSpinningFriction)) == 0u;
}

void contact_forces_lanes(Kernels& k, uint64_t begin, uint64_t end) {
  HWY_DYNAMIC_DISPATCH(ContactLanes)(k, begin, end);
}

const char* contact_lanes_target() { return HWY_DYNAMIC_DISPATCH(LanesTarget)(); }

std::vector<int64_t> contact_lanes_targets() { return hwy::SupportedAndGeneratedTargets(); }

void pin_contact_lanes_target(int64_t target) { hwy::SetSupportedTargetsForTest(target); }

void set_contact_lanes(bool on) { g_lanes_on.store(on, std::memory_order_relaxed); }
bool contact_lanes_enabled() { return g_lanes_on.load(std::memory_order_relaxed); }

}  // namespace repose::gpu
#endif
