// process_contact in SIMD lanes (contact_lanes.h). The contact law is not written here: this file
// gives the law's dialect (docs/engineering.md, "The contact law, written once") one contact per
// lane and compiles shaders/kernels/contact_law.h inside LaneLaw, the text the GLSL and scalar
// kernels compile. What is left here is memory: loading a batch of contacts' rows, gathering their
// pair parameters (every row of REPOSE_PAIR_PARAMS) and storing the entries. Compiled once per
// SIMD target by Highway's foreach_target; -ffp-contract=off keeps every Mul and Add a separate
// rounding.
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

// ---- The law's dialect, one contact per lane. ----
// Each operation is the IEEE operation of the scalar kernel (correctly rounded in every SIMD
// width); a cond converts to no bool, so an `if` on data does not compile: the law picks.
struct cond {
  M m;
};
struct real {
  V v;
  real() = default;
  real(V x) : v(x) {}
  real(float f) : v(hn::Set(D(), f)) {}
};
struct real3 {
  real x, y, z;
  real3() = default;
  real3(real a, real b, real c) : x(a), y(b), z(c) {}
  explicit real3(float f) : x(f), y(f), z(f) {}
};
inline real operator+(real a, real b) { return hn::Add(a.v, b.v); }
inline real operator-(real a, real b) { return hn::Sub(a.v, b.v); }
inline real operator*(real a, real b) { return hn::Mul(a.v, b.v); }
inline real operator-(real a) { return hn::Neg(a.v); }
inline cond operator<(real a, real b) { return {hn::Lt(a.v, b.v)}; }
inline cond operator>(real a, real b) { return {hn::Gt(a.v, b.v)}; }
inline cond operator<=(real a, real b) { return {hn::Le(a.v, b.v)}; }
inline cond operator>=(real a, real b) { return {hn::Ge(a.v, b.v)}; }
inline cond operator&&(cond a, cond b) { return {hn::And(a.m, b.m)}; }
inline cond operator||(cond a, cond b) { return {hn::Or(a.m, b.m)}; }
inline cond operator!(cond a) { return {hn::Not(a.m)}; }
// A bool is the same for every lane (the flags).
inline cond operator&&(bool a, cond b) { return a ? b : cond{hn::FirstN(D(), 0)}; }
inline cond operator&&(cond a, bool b) { return b ? a : cond{hn::FirstN(D(), 0)}; }
inline real3 operator+(real3 a, real3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline real3 operator-(real3 a, real3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
// The law divides and takes roots only through div_rn and sqrt_rn (GLSL corrects a device's
// rounding there); lanes round both correctly, so they are Div and Sqrt. No operator/ nor sqrt:
// a plain one in the law does not compile here.
inline real div_rn(real a, real b) { return hn::Div(a.v, b.v); }
inline real sqrt_rn(real a) { return hn::Sqrt(a.v); }
inline real abs(real a) { return hn::Abs(a.v); }
// std::max(a, b) and std::min(a, b) exactly: which operand wins on equal zeros and on NaN (a SIMD
// max returns its second operand there).
inline real max(real a, real b) { return hn::IfThenElse(hn::Lt(a.v, b.v), b.v, a.v); }
inline real min(real a, real b) { return hn::IfThenElse(hn::Lt(b.v, a.v), b.v, a.v); }
inline real pick(cond c, real yes, real no) { return hn::IfThenElse(c.m, yes.v, no.v); }
inline real3 pick(cond c, real3 yes, real3 no) { return {pick(c, yes.x, no.x), pick(c, yes.y, no.y), pick(c, yes.z, no.z)}; }

// The contact law in lanes: the shared text, its types and functions as members.
struct LaneLaw {
  // Each lane's pair parameters: every row of REPOSE_PAIR_PARAMS (repose_shared.h), by name.
  struct PairParams {
#define REPOSE_LANE_PARAM(name, unit, source) real name;
    REPOSE_PAIR_PARAMS(REPOSE_LANE_PARAM)
#undef REPOSE_LANE_PARAM
  };
#include "kernels/vector3.h"
#include "kernels/contact_law.h"
};

// Field `word` of the structs at indices `index`, each `stride` 4-byte words long.
V gather(const void* base, VI index, int stride, int word) {
  VI at = hn::Add(hn::Mul(index, hn::Set(DI(), stride)), hn::Set(DI(), word));
  return hn::GatherIndex(D(), static_cast<const float*>(base), at);
}
VI gather_int(const void* base, VI index, int stride, int word) {
  VI at = hn::Add(hn::Mul(index, hn::Set(DI(), stride)), hn::Set(DI(), word));
  return hn::GatherIndex(DI(), static_cast<const int32_t*>(base), at);
}

// The pair parameters of materials mi and mj in each lane, gathered row by row from the table.
HWY_INLINE LaneLaw::PairParams gather_params(Kernels& k, VI mi, VI mj) {
  const PairParams* pairs = k.B_pairs;
  VI pair = hn::Add(hn::Mul(mi, hn::Set(DI(), int(k.PC.n_materials))), mj);
  int32_t first = hn::GetLane(pair);
  LaneLaw::PairParams out;
  if (hn::AllTrue(DI(), hn::Eq(pair, hn::Set(DI(), first)))) {  // one pair (the usual case): no gathers
    const PairParams& p = pairs[first];
#define REPOSE_LANE_PARAM_SET(name, unit, source) out.name = real(p.name);
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

// integrate.h rolling_lever: the body of each lane's sphere, then the law's lever.
real rolling_lever(Kernels& k, LaneLaw& law, VI sphere, real3 cp, real r) {
  constexpr int SW = sizeof(SubSphere) / 4, BW = sizeof(Body) / 4;
  constexpr int info_x = offsetof(SubSphere, info) / 4, count = offsetof(Body, spheres) / 4 + 1;
  constexpr int centre = offsetof(Body, pos) / 4;
  VI b = gather_int(k.B_subs, sphere, SW, info_x);
  cond lone{hn::RebindMask(D(), hn::Lt(gather_int(k.B_bodies, b, BW, count), hn::Set(DI(), 2)))};
  real3 com(gather(k.B_bodies, b, BW, centre), gather(k.B_bodies, b, BW, centre + 1),
            gather(k.B_bodies, b, BW, centre + 2));
  return law.centre_of_mass_lever(cp, com, r, lone);
}

// The vec4 rows base[index[l]] of the lanes, as four vectors (x, y, z, w). One 16-byte copy per
// lane and one transpose: a gather per component costs several times more.
struct V4 {
  V x, y, z, w;
  real3 xyz() const { return {x, y, z}; }
};
V4 rows(const vec4* base, const uint* index) {
  alignas(64) float buf[4 * HWY_LANES(float)];
  const size_t L = hn::Lanes(D());
  for (size_t l = 0; l < L; ++l) std::memcpy(buf + 4 * l, base + index[l], sizeof(vec4));
  V4 r;
  hn::LoadInterleaved4(D(), buf, r.x, r.y, r.z, r.w);
  return r;
}

// contacts.h sphere_state for the lanes' owners i and partners p, the rows loaded as the pairs
// need them (i's and p's positions, velocities, spins): the partners' rows miss the cache, and
// their loads start early.
HWY_INLINE void sphere_states(Kernels& k, const uint* i, const uint* p, LaneLaw::SphereState& si, LaneLaw::SphereState& sj) {
  V4 pos_i = rows(k.B_pos, i), pos_j = rows(k.B_pos, p);
  V4 vel_i = rows(k.B_vel, i), vel_j = rows(k.B_vel, p);
  si.x = pos_i.xyz();
  si.radius = pos_i.w;
  sj.x = pos_j.xyz();
  sj.radius = pos_j.w;
  si.v = vel_i.xyz();
  si.inv_mass = vel_i.w;
  sj.v = vel_j.xyz();
  sj.inv_mass = vel_j.w;
  si.w = rows(k.B_omega, i).xyz();
  sj.w = rows(k.B_omega, p).xyz();
}

void store4(vec4* at, real x, real y, real z, real w) { hn::StoreInterleaved4(x.v, y.v, z.v, w.v, D(), &at->x); }
real zero_unless(cond c, real a) { return hn::IfThenElseZero(c.m, a.v); }
real3 zero_unless(cond c, real3 a) { return {zero_unless(c, a.x), zero_unless(c, a.y), zero_unless(c, a.z)}; }

// process_contact (contacts.h) for the Lanes(D()) contacts from c between particles i and p.
void particle_lanes(Kernels& k, uint64_t c, const uint* i_at, const uint* p_at) {
  const DI di;
  LaneLaw law;
  const uint flags = k.PC.flags;
  LaneLaw::SphereState si, sj;
  sphere_states(k, i_at, p_at, si, sj);
  LaneLaw::ContactGeometry g;
  real3 v_rel;
  cond t = law.touching_spheres(si, sj, flags, g, v_rel);
  VI i = hn::LoadU(di, reinterpret_cast<const int32_t*>(i_at));
  VI p = hn::LoadU(di, reinterpret_cast<const int32_t*>(p_at));
  if (law.centre_lever(flags) && (flags & kFlagLeanContacts) == 0u) {  // set_rolling_levers
    real3 cp = law.contact_point(si.x, g.n, g.ri);
    g.lever_i = rolling_lever(k, law, i, cp, g.ri);
    g.lever_j = rolling_lever(k, law, p, cp, g.rj);
  }
  V hx, hy, hz, hw;
  hn::LoadInterleaved4(D(), &k.B_history[c].x, hx, hy, hz, hw);
  VI mi = hn::GatherIndex(DI(), reinterpret_cast<const int32_t*>(k.B_material), i);
  VI mj = hn::GatherIndex(DI(), reinterpret_cast<const int32_t*>(k.B_material), p);
  real3 shear(hx, hy, hz);
  LaneLaw::ContactOut o = law.hertz_mindlin(g, v_rel, si.w, sj.w, false, gather_params(k, mi, mj), k.PC.dt, flags, shear);
  if ((flags & kFlagKeepHistory) == 0u) {
    real age = real(hw) + 1.0f;
    store4(&k.B_history[c], zero_unless(t, shear.x), zero_unless(t, shear.y), zero_unless(t, shear.z),
           zero_unless(t, age));
  } else {
    store4(&k.B_history[c], zero_unless(t, hx), zero_unless(t, hy), zero_unless(t, hz), zero_unless(t, hw));
  }
  real3 f = zero_unless(t, o.force_i);
  if ((flags & kFlagLeanContacts) != 0u) {
    real3 nf = zero_unless(t, o.n_x_ft);
    store4(&k.B_contact_force[c], f.x, f.y, f.z, zero_unless(t, o.roll_arm));
    store4(&k.B_torque_i[c], nf.x, nf.y, nf.z, zero_unless(t, g.overlap));
    return;
  }
  real3 ti = zero_unless(t, o.torque_i), tj = zero_unless(t, o.torque_j);
  store4(&k.B_contact_force[c], f.x, f.y, f.z, zero_unless(t, o.normal_force));
  store4(&k.B_torque_i[c], ti.x, ti.y, ti.z, 0.0f);
  store4(&k.B_torque_j[c], tj.x, tj.y, tj.z, 0.0f);
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
         (flags & kFlagsNeedFullEntries) == 0u;
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
