// The neighbour walk's rows of cells and large bucket in SIMD lanes (walk_lanes.h). Compiled once
// per SIMD target by Highway's foreach_target; -ffp-contract=off keeps every Mul and Add a separate
// rounding, so a lane's test is near_owned_pair's to the bit.
#include "walk_lanes.h"

#include <algorithm>
#include <cstring>

#include "twin_kernels.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "walk_lanes.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
#include <hwy/highway.h>

#include "lane_law.h"  // once per target, as this file (with lane_dialect.h)

HWY_BEFORE_NAMESPACE();
namespace repose::gpu::HWY_NAMESPACE {

void FillWalkRows(Kernels& k, uint64_t begin, uint64_t end) {
  const size_t n = k.PC.n_particles;
  float* x = k.walk_rows;
  uint* id = reinterpret_cast<uint*>(x + 4 * n);
  for (uint64_t s = begin; s < end; ++s) {
    const uint j = k.B_sorted[s];
    const vec4 p = k.B_pos[j];
    x[s] = p.x;
    x[n + s] = p.y;
    x[2 * n + s] = p.z;
    x[3 * n + s] = p.w;
    id[s] = k.global_id(j);
  }
}

// The slots of [s, min(s + lanes, end)) whose sphere j has a global id from `lowest` and is
// within the skin of touching sphere i (near_owned_pair(pi, pj, skin, id >= lowest): the same
// operations, d = pi - pj, (dx dx + dy dy) + dz dz < ((ri + rj) + skin)^2, where the reach times
// 0 or 1 is no reach or the reach), as bits from slot s up.
struct NearSlots {
  const D d;
  const DI di;
  const float* X;
  const int32_t* ID;
  size_t n;
  hn::Vec<D> px, py, pz, pr, skin;
  hn::Vec<DI> flip, low;  // ids compare as unsigned: with the top bit flipped, a signed compare orders them so

  NearSlots(const Kernels& k, vec4 pi, uint lowest)
      : X(k.walk_rows), ID(reinterpret_cast<const int32_t*>(k.walk_rows + 4 * size_t(k.PC.n_particles))),
        n(k.PC.n_particles), px(hn::Set(d, pi.x)), py(hn::Set(d, pi.y)), pz(hn::Set(d, pi.z)), pr(hn::Set(d, pi.w)),
        skin(hn::Set(d, k.PC.skin)), flip(hn::Set(di, int32_t(0x80000000u))),
        low(hn::Xor(hn::Set(di, int32_t(lowest)), flip)) {}

  uint64_t at(uint s, uint end) const {
    const auto dx = hn::Sub(px, hn::LoadU(d, X + s));
    const auto dy = hn::Sub(py, hn::LoadU(d, X + n + s));
    const auto dz = hn::Sub(pz, hn::LoadU(d, X + 2 * n + s));
    const auto dd = hn::Add(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), hn::Mul(dz, dz));
    const auto reach = hn::Add(hn::Add(pr, hn::LoadU(d, X + 3 * n + s)), skin);
    const auto owned = hn::RebindMask(d, hn::Not(hn::Lt(hn::Xor(hn::LoadU(di, ID + s), flip), low)));
    const auto pass = hn::And(hn::And(hn::Lt(dd, hn::Mul(reach, reach)), owned), hn::FirstN(d, end - s));
    if (hn::AllFalse(d, pass)) return 0;
    return lane_bits(d, pass);
  }
};

// walk_cells: the slots that pass NearSlots, then (when i is fixed) those whose j is not, through
// keep_in_row in slot order. (The two loops here as one template over a lambda made the walk
// 13-25 % slower, cabbage landing and pour, one round each.)
uint WalkRow(Kernels& k, uint i, vec4 pi, int x0, int x1, ivec3 c, uint begin, uint end, uint lowest, bool i_fixed,
             bool fill, uint base, uint kk, uint old_begin, uint old_end) {
  const NearSlots near(k, pi, lowest);
  const uint L = uint(hn::Lanes(D()));
  for (uint s = begin; s < end; s += L)
    for (uint64_t lanes = near.at(s, end); lanes != 0; lanes &= lanes - 1) {
      const uint j = k.B_sorted[s + uint(__builtin_ctzll(lanes))];
      if (i_fixed && k.is_fixed(j)) continue;
      kk = k.keep_in_row(i, j, k.B_pos[j], x0, x1, c, fill, base, kk, old_begin, old_end);
    }
  return kk;
}

// walk_large: the slots that pass NearSlots, then those that are not one body's two sides or two
// fixed spheres, emitted in slot order.
uint WalkLarge(Kernels& k, uint i, vec4 pi, uint lowest, uint begin, uint end, bool fill, uint base, uint kk,
               uint old_begin, uint old_end) {
  const NearSlots near(k, pi, lowest);
  const uint L = uint(hn::Lanes(D()));
  for (uint s = begin; s < end; s += L)
    for (uint64_t lanes = near.at(s, end); lanes != 0; lanes &= lanes - 1) {
      const uint j = k.B_sorted[s + uint(__builtin_ctzll(lanes))];
      if (k.no_contact(i, j)) continue;
      k.emit_candidate(fill, base, kk, i, j, old_begin, old_end);
      kk = kk + 1u;
    }
  return kk;
}

// The walk's wall tests (walls.h wall_within_skin) of the spheres in slots [first, first + lanes)
// against the walls every sphere tests (the wall grid's list, or every wall without a grid; the
// first 32 of them), in lanes where lane_wall takes the wall: plane_contact and cylinder_contact,
// the text the scalar test runs, so the same answers. Rectangles' edges and triangles stay
// scalar. A falling fill is rebuilt every few steps, and these tests, one sphere and wall at a
// time, were a tenth of the large heap's falling fill (the cylinder's root and division most of it).
struct WallsNear {
  uint first = 0;
  uint listed = 0;             // the walls every sphere tests, at most 32
  const uint* list = nullptr;  // their ids (null: walls 0 .. listed - 1)
  uint32_t tested[HWY_LANES(float)] = {}, near[HWY_LANES(float)] = {};

  explicit WallsNear(const Kernels& k) {
    const uint t = k.PC.wall_table_size;
    if (t == 0u) {
      listed = std::min(k.PC.n_walls, 32u);
    } else {
      list = k.B_wall_grid + k.B_wall_grid[t];
      listed = std::min(k.B_wall_grid[t + 1u] - k.B_wall_grid[t], 32u);
    }
  }

  // The spheres from slot i (those past the last slot take its row, and are never asked for).
  void measure(Kernels& k, uint i) {
    const size_t L = hn::Lanes(D());
    const uint last = k.PC.n_particles - 1u;
    alignas(64) vec4 at[HWY_LANES(float)];
    for (size_t l = 0; l < L; ++l) at[l] = k.B_pos[std::min(i + uint(l), last)];
    V4 x;
    hn::LoadInterleaved4(D(), &at[0].x, x.x, x.y, x.z, x.w);
    first = i;
    std::fill(tested, tested + L, 0u);
    std::fill(near, near + L, 0u);
    LaneLaw law;
    for (uint j = 0; j < listed; ++j) {
      const WallState ws = k.wall_at(list != nullptr ? list[j] : j);
      uint64_t lanes = 0;
      LaneWall kind = LaneWall::None;
      for (size_t l = 0; l < L; ++l) {
        const LaneWall lane = lane_wall(k, ws, vec3(at[l]));
        if (lane != LaneWall::None) lanes |= uint64_t(1) << l, kind = lane;
      }
      if (lanes == 0) continue;
      const bool cylinder = kind == LaneWall::Cylinder;  // one wall: every lane's kind alike
      real3 n;
      real overlap;
      const cond hit = lane_wall_contact(law, x.xyz(), x.w, same_row(ws.p0).xyz(), same_row(ws.p1), real(ws.vel.w),
                                         hn::FirstN(D(), cylinder ? L : 0), cylinder, k.PC.skin, n, overlap);
      const uint64_t hits = lane_bits(D(), hit.m);
      for (uint64_t b = lanes; b != 0; b &= b - 1) {
        const size_t l = __builtin_ctzll(b);
        tested[l] |= 1u << j;
        near[l] |= uint32_t((hits >> l) & 1u) << j;
      }
    }
  }

  // 1 or 0 where wall w was measured for the sphere in slot i, else -1.
  int answer(uint i, uint w) const {
    if (i - first >= hn::Lanes(D())) return -1;
    const uint j = list != nullptr ? uint(std::find(list, list + listed, w) - list) : w;
    if (j >= listed || ((tested[i - first] >> j) & 1u) == 0u) return -1;
    return int((near[i - first] >> j) & 1u);
  }
};

// The walk's text again with its rows, large bucket and walls in lanes: the shared text's
// functions as members that hide Kernels' own, so walk_neighbours calls WalkRow, WalkLarge and
// the walls' answers directly.
// (In a namespace of its own, where the text's min, max and abs are the twin's scalar ones, not the
// lanes' of lane_dialect.h, which take reals.)
namespace scalar_text {
using gpu::abs;
using gpu::floor;
using gpu::max;
using gpu::min;
struct LaneWalk : Kernels {
  WallsNear walls;
  explicit LaneWalk(const Kernels& k) : Kernels(k), walls(k) {}
  uint walk_row(uint i, vec4 pi, int x0, int x1, ivec3 c, uint begin, uint end, uint lowest, bool i_fixed, bool fill,
                uint base, uint k, uint old_begin, uint old_end) {
    return WalkRow(*this, i, pi, x0, x1, c, begin, end, lowest, i_fixed, fill, base, k, old_begin, old_end);
  }
  uint walk_large_bucket(uint i, vec4 pi, uint lowest, uint begin, uint end, bool fill, uint base, uint k,
                         uint old_begin, uint old_end) {
    return WalkLarge(*this, i, pi, lowest, begin, end, fill, base, k, old_begin, old_end);
  }
  bool wall_within_skin(uint i, vec4 pi, uint w) {
    const int answer = walls.answer(i, w);
    return answer >= 0 ? answer != 0 : Kernels::wall_within_skin(i, pi, w);
  }
#undef REPOSE_KERNELS_NEIGHBOUR_H  // its guard is set: Kernels has the text already
#include "kernels/neighbour.h"
};
}  // namespace scalar_text

// The wall grid's buckets of spheres [i, end) (walk_walls), asked for ahead of their walks: the
// hash scatters neighbouring cells over the table, and its first load was walk_walls' longest wait.
HWY_INLINE void prefetch_wall_buckets(scalar_text::LaneWalk& w, uint i, uint end) {
  const uint t = w.PC.wall_table_size;
  for (; i < end; ++i) {
    const ivec3 c = w.cell_of_position(vec3(w.B_pos[i]), w.PC.inv_cell);
    __builtin_prefetch(&w.B_wall_grid[w.cell_hash(c.x, c.y, c.z, t)]);
  }
}

// contact_count for slots [begin, end), the walls of each run of Lanes(D()) slots measured first.
void CountLanes(Kernels& k, uint64_t begin, uint64_t end) {
  scalar_text::LaneWalk w(k);
  const uint64_t L = hn::Lanes(D()), spheres = std::min<uint64_t>(end, k.PC.n_particles);
  for (uint64_t i = begin; i < end; ++i) {
    if ((i - begin) % L == 0u && i < spheres) {
      if (w.walls.listed != 0u) w.walls.measure(w, uint(i));
      if (k.PC.wall_table_size != 0u) prefetch_wall_buckets(w, uint(i), uint(std::min(i + L, spheres)));
    }
    w.k_contact_count(uint(i));
  }
}

// contact_fill (neighbour.h) for slots [begin, end): each candidate's place in its row counted in
// lanes (how many keys come before its own: write_candidate's insertion, equal keys in the order
// found) and its old entry found by one comparison with the old row's partners (write_candidate's
// pick: the last match). The insertion's and the search's branches mispredicted at nearly every
// step (9 % of the large heap's pour). Rows the count walk did not keep whole (more than
// kCandidateSlots), rows past the list's capacity and old rows longer than kCandidateSlots take
// the kernel's way. Same bytes.
void FillRows(Kernels& k, uint64_t begin, uint64_t end) {
  const DI di;
  const size_t L = hn::Lanes(di);
  static_assert(kCandidateSlots % HWY_LANES(float) == 0, "a row's keys fill whole vectors");
  const bool springs = (k.PC.flags & kFlagRollingSpring) != 0u;
  const uint old_used = k.B_control[kCtlOldContacts];
  alignas(64) int32_t keys[kCandidateSlots], old[kCandidateSlots];
  for (uint i = uint(begin); i < std::min<uint64_t>(end, k.PC.n_particles); ++i) {
    const uint base = k.B_row_start[i], count = k.B_row_start[i + 1u] - base;
    const uint old_begin = k.B_old_row_start[i], old_end = std::min(k.B_old_row_start[i + 1u], old_used);
    const uint olds = old_end > old_begin ? old_end - old_begin : 0u;
    if (count > kCandidateSlots || olds > kCandidateSlots || uint64_t(base) + count > k.PC.capacity) {
      k.k_contact_fill(i);
      continue;
    }
    if (count == 0u) continue;  // a falling fill's spheres mostly: nothing to write
    const uint* found = k.B_candidates + size_t(i) * kCandidateSlots;
    const size_t key_lanes = (count + L - 1) / L * L, old_lanes = (olds + L - 1) / L * L;
    // The keys with the top bit flipped, so that a signed compare orders them as unsigned; a
    // padding key sorts after every key, a padding partner (~0u) matches none.
    for (uint q = 0; q < key_lanes; ++q)
      keys[q] = q < count ? int32_t(k.partner_key(found[q]) ^ 0x80000000u) : int32_t(0x7fffffff);
    for (uint q = 0; q < old_lanes; ++q) old[q] = q < olds ? int32_t(k.B_old_partner[old_begin + q]) : -1;
    for (uint q = 0; q < count; ++q) {
      const VI key = hn::Set(di, keys[q]), p = hn::Set(di, int32_t(found[q]));
      size_t rank = 0;
      uint64_t match = 0;
      for (size_t b = 0; b < key_lanes; b += L) {
        const VI chunk = hn::Load(di, keys + b);
        const auto before = hn::And(hn::Eq(chunk, key), hn::FirstN(di, q > b ? q - b : 0));
        rank += hn::CountTrue(di, hn::Or(hn::Lt(chunk, key), before));
      }
      for (size_t b = 0; b < old_lanes; b += L) match |= lane_bits(di, hn::Eq(hn::Load(di, old + b), p)) << b;
      const uint slot = base + uint(rank);
      const bool kept = match != 0u;
      const uint from = kept ? old_begin + 63u - uint(__builtin_clzll(match)) : 0u;
      k.B_owner[slot] = i;
      k.B_partner[slot] = found[q];
      k.B_history[slot] = kept ? k.B_old_history[from] : vec4(0.0f);
      if (springs) k.B_rolling_spring[slot] = kept ? k.B_rolling_spring[k.PC.capacity + from] : vec4(0.0f);
    }
  }
}

}  // namespace repose::gpu::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace repose::gpu {

HWY_EXPORT(FillWalkRows);
HWY_EXPORT(CountLanes);
HWY_EXPORT(FillRows);

// The padding after the ids: a whole vector of the widest target Highway has (256 B, SVE's and
// RVV's at most; AVX-512's is 64) may load from the last slot. HWY_MAX_BYTES here is the last
// target's compiled, not the widest: with it the lanes read past the arena's end.
size_t walk_rows_floats(size_t n) { return 5 * n + 256 / sizeof(float); }

void fill_walk_rows(Kernels& k, uint64_t begin, uint64_t end) { HWY_DYNAMIC_DISPATCH(FillWalkRows)(k, begin, end); }

void contact_count_lanes(Kernels& k, uint64_t begin, uint64_t end) { HWY_DYNAMIC_DISPATCH(CountLanes)(k, begin, end); }

void contact_fill_lanes(Kernels& k, uint64_t begin, uint64_t end) { HWY_DYNAMIC_DISPATCH(FillRows)(k, begin, end); }

}  // namespace repose::gpu
#endif
