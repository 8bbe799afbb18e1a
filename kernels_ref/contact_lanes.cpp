// process_contact in SIMD lanes (contact_lanes.h). The contact law is not written here: this file
// takes the law's dialect (docs/engineering.md, "The contact law, written once") one contact per
// lane (lane_dialect.h) and compiles shaders/kernels/contact_law.h inside LaneLaw, the text the
// GLSL and scalar kernels compile. What is left here is memory: loading a batch of contacts' rows, gathering their
// pair parameters (every row of REPOSE_PAIR_PARAMS) and storing the entries. Compiled once per
// SIMD target by Highway's foreach_target; -ffp-contract=off keeps every Mul and Add a separate
// rounding.
#include "contact_lanes.h"

#include <cstddef>
#include <cstring>
#include <vector>

#include "lane_switches.h"
#include "twin_kernels.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "contact_lanes.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
#include <hwy/highway.h>

#include "lane_law.h"  // once per target, as this file (with lane_dialect.h)

HWY_BEFORE_NAMESPACE();
namespace repose::gpu::HWY_NAMESPACE {

// The material every particle has, or -1 when they differ (Buffers::uniform_material; a run of
// one material has it whatever the buffers say). The walls' materials may differ either way.
HWY_INLINE int32_t one_material(const Kernels& k) { return k.PC.n_materials == 1u ? 0 : k.uniform_material; }

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

// integrate.h rolling_lever: the body of each lane's sphere, then the law's lever. A batch's owners
// are mostly one body's sub-spheres, and often its partners too: their body's row then loads once;
// otherwise each lane's row is joined in registers (body_rows()). Scalar loads of the bodies'
// indices and rows: gathers of them waited longest of the kernel's instructions (perf, a clump heap).
real rolling_lever(Kernels& k, LaneLaw& law, const uint* spheres, real3 cp, real r) {
  uint body[HWY_LANES(float)];
  bool one_body = true;
  for (size_t l = 0; l < hn::Lanes(D()); ++l) {
    body[l] = k.B_subs[spheres[block_order(l)]].info.x;  // lane l is entry block_order(l)
    one_body = one_body && body[l] == body[0];
  }
  if (one_body) {  // the usual case
    const Body& b = k.B_bodies[body[0]];
    cond lone{hn::RebindMask(D(), hn::Lt(hn::Set(DI(), int32_t(b.spheres.y)), hn::Set(DI(), 2)))};
    return law.centre_of_mass_lever(cp, real3(b.pos.x, b.pos.y, b.pos.z), r, lone);
  }
  const V4 centre = body_rows(k, body, offsetof(Body, pos) / sizeof(vec4));
  const V4 counts = body_rows(k, body, offsetof(Body, spheres) / sizeof(vec4));  // uints: their bits
  cond lone{hn::RebindMask(D(), hn::Lt(hn::BitCast(DI(), counts.y), hn::Set(DI(), 2)))};
  return law.centre_of_mass_lever(cp, centre.xyz(), r, lone);
}

// The owners' rows of a batch of a bed: the list is in rows by owner slot, so a batch's owners are
// a few consecutive slots. When every owner lies within the lanes' count of the first one, the
// rows from the first are loaded as a block (in block order) and each lane takes its owner's by a
// permutation (`lane`: where that row lies in the block's lanes); otherwise (or past the buffer's
// end) rows() joins them one by one.
HWY_INLINE bool owner_block(const uint* i, uint n, VI& offset) {
  const DI di;
  const size_t L = hn::Lanes(di);
  const uint first = i[0];
  if (first + L > n) return false;
  offset = hn::Sub(hn::LoadU(di, reinterpret_cast<const int32_t*>(i)), hn::Set(di, int32_t(first)));
  const hn::RebindToUnsigned<DI> du;  // an owner below the first wraps to a large offset
  return hn::AllTrue(du, hn::Lt(hn::BitCast(du, offset), hn::Set(du, uint32_t(L))));
}
HWY_INLINE V4 owner_rows(const vec4* base, const uint* i, bool block, VI lane) {
  if (!block) return rows<true>(base, i);
  const V4 r = load4_block_order(&base[i[0]]);
  const auto at = hn::IndicesFromVec(D(), lane);
  return {hn::TableLookupLanes(r.x, at), hn::TableLookupLanes(r.y, at), hn::TableLookupLanes(r.z, at),
          hn::TableLookupLanes(r.w, at)};
}
// The entries' indices `at` (owners, partners) in the batch's lanes.
HWY_INLINE VI lane_indices(const uint* at) {
  const DI di;
  const VI v = hn::LoadU(di, reinterpret_cast<const int32_t*>(at));
  return hn::TableLookupLanes(v, hn::IndicesFromVec(di, block_order(di)));
}

// contacts.h sphere_state for the lanes' owners and partners, the rows loaded as the pairs need
// them (positions, velocities, spins of both): the partners' rows miss the cache, and their loads
// start early. `owner(base)` and `partner(base)` load a buffer's rows of the batch's owners and
// partners.
template <class OwnerRows, class PartnerRows>
HWY_INLINE void sphere_states(Kernels& k, OwnerRows owner, PartnerRows partner, LaneLaw::SphereState& si,
                              LaneLaw::SphereState& sj) {
  V4 pos_i = owner(k.B_pos), pos_j = partner(k.B_pos);
  V4 vel_i = owner(k.B_vel), vel_j = partner(k.B_vel);
  si.x = pos_i.xyz();
  si.radius = pos_i.w;
  sj.x = pos_j.xyz();
  sj.radius = pos_j.w;
  si.v = vel_i.xyz();
  si.inv_mass = vel_i.w;
  sj.v = vel_j.xyz();
  sj.inv_mass = vel_j.w;
  si.w = owner(k.B_omega).xyz();
  sj.w = partner(k.B_omega).xyz();
}

// What process_contact stores for a batch of touching or apart pairs, row by row: the history
// (the turned spring and its age, or as it was when kept), the force, T_i (or the lean entry's
// n x Ft and overlap) and T_j; zeros where the pair does not touch. particle_lanes stores them,
// and the bench's law-alone ceiling (LawOnly) computes the same.
struct EntryRows {
  V4 history, force, third, torque_j;
};
HWY_INLINE V4 row_unless(cond t, real3 a, real w) {
  return {zero_unless(t, a.x).v, zero_unless(t, a.y).v, zero_unless(t, a.z).v, zero_unless(t, w).v};
}
HWY_INLINE EntryRows entry_rows(cond t, uint flags, const V4& hist, real3 shear, const LaneLaw::ContactOut& o,
                                const LaneLaw::ContactGeometry& g) {
  const bool keep = (flags & kFlagKeepHistory) != 0u;
  EntryRows e;
  e.history = keep ? row_unless(t, hist.xyz(), hist.w) : row_unless(t, shear, real(hist.w) + 1.0f);
  if ((flags & kFlagLeanContacts) != 0u) {
    e.force = row_unless(t, o.force_i, o.roll_arm);
    e.third = row_unless(t, o.n_x_ft, g.overlap);
    e.torque_j = row_unless(t, real3(0.0f), 0.0f);  // a lean entry has none
    return e;
  }
  e.force = row_unless(t, o.force_i, o.normal_force);
  e.third = row_unless(t, o.torque_i, 0.0f);
  e.torque_j = row_unless(t, o.torque_j, 0.0f);
  return e;
}
// The rows of a batch of pairs all apart: zeros, what the law would give them.
HWY_INLINE EntryRows apart_rows() {
  const V zero = hn::Zero(D());
  const V4 row{zero, zero, zero, zero};
  return {row, row, row, row};
}
// A batch's entries from c (a lean entry has no T_j).
HWY_INLINE void store_entries(Kernels& k, uint64_t c, const EntryRows& e, uint flags) {
  store4_block_order(&k.B_history[c], e.history);
  store4_block_order(&k.B_contact_force[c], e.force);
  store4_block_order(&k.B_torque_i[c], e.third);
  if ((flags & kFlagLeanContacts) == 0u) store4_block_order(&k.B_torque_j[c], e.torque_j);
}

// The walls of a batch measured in its lanes (planes, rectangles whose face the owner lies over,
// cylinders: lane_wall), a row per lane (wall_row: where a moving wall stands this step), by the
// shared text (plane_contact, cylinder_contact, wall_geometry) that touch_wall runs one contact at a
// time. A cylinder's rows are a plane's: base and axis in point and normal, radius normal.w,
// height vel.w.
struct LaneWalls {
  M at;        // the lanes whose partner is such a wall
  M cylinder;  // those of them that are cylinders
  bool any_cylinder;
  V4 point, normal, vel, omega, centre;
  VI material;
};
HWY_INLINE cond no_lanes() { return {hn::FirstN(D(), 0)}; }

// The wall lanes' geometry, relative velocity and touching in place of the pair's.
HWY_INLINE void measure_walls(LaneLaw& law, const LaneWalls& q, const LaneLaw::SphereState& si, uint flags,
                              LaneLaw::ContactGeometry& g, real3& v_rel, cond& t) {
  real overlap;
  real3 n;
  const cond near = lane_wall_contact(law, si.x, si.radius, q.point.xyz(), q.normal, real(q.vel.w), q.cylinder,
                                      q.any_cylinder, 0.0f, n, overlap);
  LaneLaw::ContactGeometry gw;
  real3 vw;
  law.wall_geometry(si, n, overlap, q.vel.xyz(), q.omega.xyz(), q.centre.xyz(), flags, gw, vw);
  const cond wall{q.at};
  g.n = pick(wall, gw.n, g.n);
  g.overlap = pick(wall, gw.overlap, g.overlap);
  g.radius_star = pick(wall, gw.radius_star, g.radius_star);
  g.mass_star = pick(wall, gw.mass_star, g.mass_star);
  g.ri = pick(wall, gw.ri, g.ri);
  g.rj = pick(wall, gw.rj, g.rj);
  g.lever_i = pick(wall, gw.lever_i, g.lever_i);
  g.lever_j = pick(wall, gw.lever_j, g.lever_j);
  g.cohesion_lens = pick(wall, gw.cohesion_lens, g.cohesion_lens);
  v_rel = pick(wall, vw, v_rel);
  const cond touches = near && overlap > 0.0f;  // touch_wall's test
  t = cond{hn::Or(hn::And(q.at, touches.m), hn::AndNot(q.at, t.m))};
}

// process_contact (contacts.h) for the Lanes(D()) contacts from c between particles i and p, in
// block order (lane λ contact c + block_order(λ): its rows load and store with fewer shuffles,
// lane_dialect.h). With `walls` (in that order too), its lanes are contacts with those walls
// (p_at holds their owners there).
HWY_FLATTEN void particle_lanes(Kernels& k, uint64_t c, const uint* i_at, const uint* p_at,
                                const LaneWalls* walls = nullptr) {
  const DI di;
  LaneLaw law;
  const uint flags = k.PC.flags;
  LaneLaw::SphereState si, sj;
  // A clump's sub-spheres sit in runs of slots a body long, and so do their partners: their rows
  // stay in cache, where joining them in registers is faster (the stalk bucket at rest, 2.07-2.09
  // against 1.86-1.97 CPU-s per 400 steps); a bed's partners miss it (lane_dialect.h), while its
  // owners, a few consecutive slots, stay in cache and load as a block (docs/engineering.md).
  if ((flags & kFlagBodies) != 0u) {
    sphere_states(k, [&](const vec4* base) { return rows<true>(base, i_at); },
                  [&](const vec4* base) { return rows<true>(base, p_at); }, si, sj);
  } else {
    VI offset = hn::Zero(di);
    const bool block = owner_block(i_at, k.PC.n_particles, offset);
    // Lane λ's owner is row offset[block_order(λ)] of the block, in lane block_order_lane() of it.
    const VI lane = block_order_lane(di, hn::TableLookupLanes(offset, hn::IndicesFromVec(di, block_order(di))));
    sphere_states(k, [&](const vec4* base) { return owner_rows(base, i_at, block, lane); },
                  [&](const vec4* base) { return rows_via_buffer_block_order(base, p_at); }, si, sj);
  }
  LaneLaw::ContactGeometry g;
  real3 v_rel;
  cond t = law.touching_spheres(si, sj, flags, g, v_rel);
  if (walls != nullptr) measure_walls(law, *walls, si, flags, g, v_rel, t);
  if (hn::AllFalse(D(), t.m)) return store_entries(k, c, apart_rows(), flags);  // a clump heap's list is mostly such
  if (law.centre_lever(flags) && (flags & kFlagLeanContacts) == 0u) {  // set_rolling_levers
    real3 cp = law.contact_point(si.x, g.n, g.ri);
    g.lever_i = rolling_lever(k, law, i_at, cp, g.ri);
    g.lever_j = rolling_lever(k, law, p_at, cp, g.rj);  // a wall's lane: unread (its arm_j is -1)
  }
  const V4 hist = load4_block_order(&k.B_history[c]);
  // Every particle of one material (the walls' may differ): no gathers, which are slow on this AMD
  // EPYC (7 % of the lanes' samples on a bed in cache, more in a clump heap).
  const int32_t one = one_material(k);
  VI mi = hn::Set(di, one), mj = mi;
  if (one < 0) {
    mi = hn::GatherIndex(di, reinterpret_cast<const int32_t*>(k.B_material), lane_indices(i_at));
    mj = hn::GatherIndex(di, reinterpret_cast<const int32_t*>(k.B_material), lane_indices(p_at));
  }
  if (walls != nullptr) mj = hn::IfThenElse(hn::RebindMask(di, walls->at), walls->material, mj);
  real3 shear = hist.xyz();
  // A wall's spin is not j's: touch_wall gives the law none.
  const cond wall = walls != nullptr ? cond{walls->at} : no_lanes();
  const real3 w_j = walls != nullptr ? zero_unless(!wall, sj.w) : sj.w;
  LaneLaw::ContactOut o = law.hertz_mindlin(g, v_rel, si.w, w_j, wall, gather_params(k, mi, mj), k.PC.dt, flags, shear);
  store_entries(k, c, entry_rows(t, flags, hist, shear, o, g), flags);
}

// Wall contacts waiting for a batch of lanes. The scalar kernel's touch_wall measures each (the
// kinds the lanes do not: rectangles' edges and corners, mesh triangles with their shadowing), then the law
// runs in lanes with j a wall for the whole batch: the law is most of a wall contact's cost
// (process_contact and touch_wall were 7 % of the LIGGGHTS bed's samples, 5 of them the law).
struct WallBatch {
  enum Field { Nx, Ny, Nz, Overlap, RadiusStar, MassStar, Ri, Rj, LeverI, LeverJ, Lens, Vx, Vy, Vz,
               Wx, Wy, Wz, Hx, Hy, Hz, Hw, kFields };
  size_t n = 0;
  uint c[HWY_LANES(float)];
  int32_t mi[HWY_LANES(float)], mj[HWY_LANES(float)];
  alignas(64) float f[kFields][HWY_LANES(float)];

  void add(uint contact, uint material_i, const Kernels::ContactState& st, vec3 w_i, vec4 hist) {
    const float values[kFields] = {st.g.n.x, st.g.n.y, st.g.n.z, st.g.overlap, st.g.radius_star, st.g.mass_star,
                                   st.g.ri, st.g.rj, st.g.lever_i, st.g.lever_j, st.g.cohesion_lens,
                                   st.v_rel.x, st.v_rel.y, st.v_rel.z, w_i.x, w_i.y, w_i.z,
                                   hist.x, hist.y, hist.z, hist.w};
    for (int k = 0; k < kFields; ++k) f[k][n] = values[k];
    c[n] = contact;
    mi[n] = int32_t(material_i);
    mj[n] = int32_t(st.mj);
    ++n;
  }
  real at(Field k) const { return hn::Load(D(), f[k]); }
  real3 at3(Field k) const { return {at(k), at(Field(k + 1)), at(Field(k + 2))}; }
};

// process_contact's law and stores for the batch's wall contacts (all touching), then empty.
HWY_FLATTEN void run_wall_batch(Kernels& k, WallBatch& q) {
  if (q.n == 0) return;
  const size_t L = hn::Lanes(D());
  for (size_t l = q.n; l < L; ++l) {  // idle lanes repeat the first contact; only q.n are stored
    for (int f = 0; f < WallBatch::kFields; ++f) q.f[f][l] = q.f[f][0];
    q.mi[l] = q.mi[0];
    q.mj[l] = q.mj[0];
  }
  const uint flags = k.PC.flags;
  LaneLaw law;
  LaneLaw::ContactGeometry g;
  g.n = q.at3(WallBatch::Nx);
  g.overlap = q.at(WallBatch::Overlap);
  g.radius_star = q.at(WallBatch::RadiusStar);
  g.mass_star = q.at(WallBatch::MassStar);
  g.ri = q.at(WallBatch::Ri);
  g.rj = q.at(WallBatch::Rj);
  g.lever_i = q.at(WallBatch::LeverI);
  g.lever_j = q.at(WallBatch::LeverJ);
  g.cohesion_lens = q.at(WallBatch::Lens);
  real3 shear = q.at3(WallBatch::Hx);
  VI mi = hn::LoadU(DI(), q.mi), mj = hn::LoadU(DI(), q.mj);
  LaneLaw::ContactOut o = law.hertz_mindlin(g, q.at3(WallBatch::Vx), q.at3(WallBatch::Wx), real3(0.0f), !no_lanes(),
                                            gather_params(k, mi, mj), k.PC.dt, flags, shear);
  alignas(64) vec4 history[HWY_LANES(float)], force[HWY_LANES(float)], ti[HWY_LANES(float)], tj[HWY_LANES(float)];
  store4(history, shear.x, shear.y, shear.z, q.at(WallBatch::Hw) + 1.0f);
  const bool lean = (flags & kFlagLeanContacts) != 0u;
  if (lean) {
    store4(force, o.force_i.x, o.force_i.y, o.force_i.z, o.roll_arm);
    store4(ti, o.n_x_ft.x, o.n_x_ft.y, o.n_x_ft.z, g.overlap);
  } else {
    store4(force, o.force_i.x, o.force_i.y, o.force_i.z, o.normal_force);
    store4(ti, o.torque_i.x, o.torque_i.y, o.torque_i.z, 0.0f);
    store4(tj, o.torque_j.x, o.torque_j.y, o.torque_j.z, 0.0f);
  }
  for (size_t l = 0; l < q.n; ++l) {
    uint c = q.c[l];
    if ((flags & kFlagKeepHistory) == 0u) k.B_history[c] = history[l];
    k.B_contact_force[c] = force[l];
    k.B_torque_i[c] = ti[l];
    if (!lean) k.B_torque_j[c] = tj[l];
  }
  q.n = 0;
}

// The rows of the batch's lane walls (`row`, each lane's; `lanes`, their bits; `cylinders`, the
// cylinders' among them). Mostly one wall (an owner by the floor): its rows are broadcast;
// otherwise each lane's joined, a lane without one taking the first one's, which its pick ignores.
// `lanes` and `row` are by entry; lane λ takes entry block_order(λ)'s.
LaneWalls wall_rows(const Kernels& k, const uint* row, uint64_t lanes, uint64_t cylinders) {
  constexpr uint kRow = sizeof(WallState) / sizeof(vec4);
  static_assert(sizeof(WallState) % sizeof(vec4) == 0, "a WallState is whole vec4 rows");
  auto mask = [](uint64_t b) {
    uint8_t bits[8] = {};
    std::memcpy(bits, &b, sizeof(bits));
    const M m = hn::LoadMaskBits(D(), bits);
    const D d;
    return hn::MaskFromVec(hn::TableLookupLanes(hn::VecFromMask(d, m), hn::IndicesFromVec(d, block_order(DI()))));
  };
  const uint first = row[__builtin_ctzll(lanes)];
  bool one = true;
  for (uint64_t b = lanes; b != 0; b &= b - 1) one = one && row[__builtin_ctzll(b)] == first;
  const size_t L = hn::Lanes(D());
  uint index[HWY_LANES(float)];
  alignas(64) int32_t material[HWY_LANES(float)];
  for (size_t l = 0; l < L && !one; ++l) {
    const size_t e = block_order(l);
    const uint r = (lanes >> e) & 1u ? row[e] : first;
    index[l] = r * kRow;
    material[l] = int32_t(k.B_walls[r].info.y);
  }
  const vec4* walls = reinterpret_cast<const vec4*>(k.B_walls);
  auto field = [&](size_t offset) {
    const vec4* base = walls + offset / sizeof(vec4);
    return one ? same_row(base[first * kRow]) : rows(base, index);
  };
  return {mask(lanes),
          mask(cylinders),
          cylinders != 0,
          field(offsetof(WallState, p0)),
          field(offsetof(WallState, p1)),
          field(offsetof(WallState, vel)),
          field(offsetof(WallState, omega)),
          field(offsetof(WallState, centre)),
          one ? hn::Set(DI(), int32_t(k.B_walls[first].info.y)) : hn::Load(DI(), material)};
}

// A batch with walls (they sort last in a row): its particle pairs in lanes, the walls' lanes run
// as a contact of the owner with itself (centres coincide: not touching). Planes, rectangles' faces
// and cylinders are then measured in those lanes (measure_walls); any other wall's lane (a
// rectangle's edge, a mesh triangle) keeps its history aside, and
// after the lanes each such contact is measured, stored as apart or added to the wall batch. A
// bed's mixed batches are many (an owner by a wall in ~4 of every 10 batches), its wall lanes few.
void mixed_lanes(Kernels& k, uint64_t c, VI partners, M walls_at, WallBatch& walls) {
  const DI di;
  const size_t L = hn::Lanes(di);
  const auto wall_lanes = hn::RebindMask(di, walls_at);
  alignas(64) uint partner[HWY_LANES(float)];
  hn::Store(hn::IfThenElse(wall_lanes, hn::LoadU(di, reinterpret_cast<const int32_t*>(k.B_owner + c)), partners), di,
            reinterpret_cast<int32_t*>(partner));
  uint64_t lanes = lane_bits(di, wall_lanes), in_lanes = 0, cylinders = 0;
  uint row[HWY_LANES(float)];
  for (uint64_t b = lanes; b != 0; b &= b - 1) {
    const size_t l = __builtin_ctzll(b);
    row[l] = k.wall_row(k.B_partner[c + l] - k.PC.n_particles);
    const LaneWall kind = lane_wall(k, k.B_walls[row[l]], vec3(k.B_pos[k.B_owner[c + l]]));
    if (kind != LaneWall::None) in_lanes |= uint64_t(1) << l;
    if (kind == LaneWall::Cylinder) cylinders |= uint64_t(1) << l;
  }
  lanes &= ~in_lanes;  // the walls measured one by one
  vec4 history[HWY_LANES(float)];
  for (uint64_t b = lanes; b != 0; b &= b - 1) {
    const size_t l = __builtin_ctzll(b);
    history[l] = k.B_history[c + l];
  }
  if (in_lanes != 0) {
    const LaneWalls rows = wall_rows(k, row, in_lanes, cylinders);
    particle_lanes(k, c, k.B_owner + c, partner, &rows);
  } else {
    particle_lanes(k, c, k.B_owner + c, partner);
  }
  const int32_t one = one_material(k);
  for (uint64_t b = lanes; b != 0; b &= b - 1) {
    const size_t l = __builtin_ctzll(b);
    uint p = k.B_partner[c + l];
    uint i = k.B_owner[c + l], contact = uint(c + l);
    k.B_history[contact] = history[l];
    Kernels::ContactState st;
    if (!k.touch_wall(i, contact, p, st)) {  // apart: process_contact's zeros (no rolling springs here)
      k.B_history[contact] = vec4(0.0f);
      k.B_contact_force[contact] = vec4(0.0f);
      k.B_torque_i[contact] = vec4(0.0f);
      if ((k.PC.flags & kFlagLeanContacts) == 0u) k.B_torque_j[contact] = vec4(0.0f);
      continue;
    }
    walls.add(contact, one >= 0 ? uint(one) : k.B_material[i], st, vec3(k.B_omega[i]), history[l]);
    if (walls.n == L) run_wall_batch(k, walls);
  }
}

void ContactLanes(Kernels& k, uint64_t begin, uint64_t end) {
  const DI di;
  const size_t L = hn::Lanes(di);
  const VI particles = hn::Set(di, int32_t(k.PC.n_particles));
  WallBatch walls;
  uint64_t c = begin;
  for (; c + L <= end; c += L) {
    VI p = hn::LoadU(di, reinterpret_cast<const int32_t*>(k.B_partner + c));
    // The histories' stream, 8 batches ahead, a 64-byte line (4 entries) at a time: its loads
    // were the kernel's longest wait.
    if (c + 9 * L <= end)
      for (size_t e = 0; e < L; e += 4) __builtin_prefetch(&k.B_history[c + 8 * L + e]);
    const auto walls_at = hn::Not(hn::Lt(p, particles));
    if (hn::AllFalse(di, walls_at))
      particle_lanes(k, c, k.B_owner + c, k.B_partner + c);
    else
      mixed_lanes(k, c, p, hn::RebindMask(D(), walls_at), walls);
  }
  run_wall_batch(k, walls);
  for (; c < end; ++c) k.process_contact(k.B_owner[c], uint(c));
}

// The law's arithmetic alone, for the bench's compute ceiling (contact_lanes.h): kLawRing batches
// of the list's particle pairs, spread over it, their rows copied once into lanes' layout (14 KB
// at 16 lanes, within L1), then particle_lanes' law, picks and stores run `batches` times over
// them, storing into `sink` the rows particle_lanes stores in the entries (entry_rows), batch after
// batch.
struct RingBatch {
  enum Field { Xi = 0, Ri = 3, Vi = 4, Mi = 7, Wi = 8, Xj = 11, Rj = 14, Vj = 15, Mj = 18, Wj = 19, H = 22, kFields = 26 };
  alignas(64) float f[kFields][HWY_LANES(float)];
  alignas(64) int32_t mi[HWY_LANES(float)], mj[HWY_LANES(float)];
  real at(int field) const { return hn::Load(D(), f[field]); }
  real3 at3(int field) const { return {at(field), at(field + 1), at(field + 2)}; }
};

// The ring's batches from the list (false when it holds no particle pair).
bool fill_ring(Kernels& k, std::vector<RingBatch>& ring) {
  const size_t L = hn::Lanes(D());
  const uint64_t n = k.B_control[kCtlContacts];
  uint64_t c = 0;
  for (size_t b = 0; b < ring.size(); ++b) {
    for (size_t l = 0; l < L; ++l, c = (c + 1) % n) {
      for (uint64_t tried = 0; k.B_partner[c] >= k.PC.n_particles; c = (c + 1) % n)  // particle pairs only
        if (++tried > n) return false;
      const uint i = k.B_owner[c], j = k.B_partner[c];
      const vec4 rows[] = {k.B_pos[i], k.B_vel[i], k.B_omega[i], k.B_pos[j], k.B_vel[j], k.B_omega[j], k.B_history[c]};
      const int first[] = {RingBatch::Xi, RingBatch::Vi, RingBatch::Wi, RingBatch::Xj, RingBatch::Vj, RingBatch::Wj,
                           RingBatch::H};
      for (int r = 0; r < 7; ++r)
        for (int w = 0; w < (r % 3 == 2 && r < 6 ? 3 : 4); ++w) ring[b].f[first[r] + w][l] = (&rows[r].x)[w];
      ring[b].mi[l] = int32_t(k.B_material[i]);
      ring[b].mj[l] = int32_t(k.B_material[j]);
    }
    c = (b + 1) * n / ring.size();  // the next batch further along the list
  }
  return true;
}

HWY_FLATTEN void LawOnly(Kernels& k, uint64_t batches, float* sink) {
  std::vector<RingBatch> ring(kLawRing);
  if (k.B_control[kCtlContacts] == 0 || !fill_ring(k, ring)) return;
  const size_t L = hn::Lanes(D());
  const uint flags = k.PC.flags;
  LaneLaw law;
  for (uint64_t n = 0; n < batches; ++n) {
    const RingBatch& q = ring[n % kLawRing];
    float* out = sink + (n % kLawRing) * kSinkFloats * L;
    auto put = [&](int at, real x) { hn::StoreU(x.v, D(), out + at * L); };
    LaneLaw::SphereState si{q.at3(RingBatch::Xi), q.at(RingBatch::Ri), q.at3(RingBatch::Vi), q.at(RingBatch::Mi),
                            q.at3(RingBatch::Wi)};
    LaneLaw::SphereState sj{q.at3(RingBatch::Xj), q.at(RingBatch::Rj), q.at3(RingBatch::Vj), q.at(RingBatch::Mj),
                            q.at3(RingBatch::Wj)};
    LaneLaw::ContactGeometry g;
    real3 v_rel;
    cond t = law.touching_spheres(si, sj, flags, g, v_rel);
    EntryRows e = apart_rows();
    if (!hn::AllFalse(D(), t.m)) {
      const V4 hist{q.at(RingBatch::H).v, q.at(RingBatch::H + 1).v, q.at(RingBatch::H + 2).v, q.at(RingBatch::H + 3).v};
      real3 shear = hist.xyz();
      VI mi = hn::Load(DI(), q.mi), mj = hn::Load(DI(), q.mj);
      LaneLaw::ContactOut o =
          law.hertz_mindlin(g, v_rel, si.w, sj.w, no_lanes(), gather_params(k, mi, mj), k.PC.dt, flags, shear);
      e = entry_rows(t, flags, hist, shear, o, g);
    }
    const V4* rows[4] = {&e.history, &e.force, &e.third, &e.torque_j};
    for (int r = 0; r < 4; ++r) {
      put(4 * r, rows[r]->x);
      put(4 * r + 1, rows[r]->y);
      put(4 * r + 2, rows[r]->z);
      put(4 * r + 3, rows[r]->w);
    }
  }
}

const char* LanesTarget() { return hwy::TargetName(HWY_TARGET); }
size_t LanesWidth() { return hn::Lanes(D()); }

}  // namespace repose::gpu::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace repose::gpu {

HWY_EXPORT(ContactLanes);
HWY_EXPORT(LanesTarget);
HWY_EXPORT(LawOnly);
HWY_EXPORT(LanesWidth);

bool contact_lanes_cover(uint flags) {
  return lanes_enabled(LaneKernels::Contacts) &&
         (flags & kFlagsNeedFullEntries) == 0u;
}

void contact_forces_lanes(Kernels& k, uint64_t begin, uint64_t end) {
  HWY_DYNAMIC_DISPATCH(ContactLanes)(k, begin, end);
}

void contact_law_lanes(Kernels& k, uint64_t batches, float* sink) { HWY_DYNAMIC_DISPATCH(LawOnly)(k, batches, sink); }

size_t contact_lanes_width() { return HWY_DYNAMIC_DISPATCH(LanesWidth)(); }

const char* contact_lanes_target() { return HWY_DYNAMIC_DISPATCH(LanesTarget)(); }

std::vector<int64_t> contact_lanes_targets() { return hwy::SupportedAndGeneratedTargets(); }

void pin_contact_lanes_target(int64_t target) { hwy::SetSupportedTargetsForTest(target); }


}  // namespace repose::gpu
#endif
