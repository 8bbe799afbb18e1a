// The neighbour walk's rows in SIMD lanes (walk_lanes.h). Compiled once per SIMD target by
// Highway's foreach_target; -ffp-contract=off keeps every Mul and Add a separate rounding, so a
// lane's test is near_owned_pair's to the bit.
#include "walk_lanes.h"

#include "twin_kernels.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "walk_lanes.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace repose::gpu::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<D>;

void FillWalkRows(Kernels& k, uint64_t begin, uint64_t end) {
  const size_t n = k.PC.n_particles;
  float* x = const_cast<float*>(k.walk_rows);
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

// walk_cells(...) with the id and distance tests of a lane's worth of slots at a time: a slot
// passes when near_owned_pair(pi, pj, skin, id >= lowest) (the same operations: d = pi - pj,
// (dx dx + dy dy) + dz dz < ((ri + rj) + skin)^2, the reach times 0 or 1 being the reach or no
// reach) and, when i is fixed, j is not; then keep_in_row as walk_cells does.
uint WalkRow(Kernels& k, uint i, vec4 pi, int x0, int x1, ivec3 c, uint begin, uint end, uint lowest, bool i_fixed,
             bool fill, uint base, uint kk, uint old_begin, uint old_end) {
  const D d;
  const DI di;
  const size_t L = hn::Lanes(d), n = k.PC.n_particles;
  const float* X = k.walk_rows;
  const uint* ID = reinterpret_cast<const uint*>(X + 4 * n);
  const auto px = hn::Set(d, pi.x), py = hn::Set(d, pi.y), pz = hn::Set(d, pi.z), pr = hn::Set(d, pi.w);
  const auto skin = hn::Set(d, k.PC.skin);
  // Ids compare as unsigned: with the top bit flipped, a signed compare orders them so.
  const auto flip = hn::Set(di, int32_t(0x80000000u)), low = hn::Xor(hn::Set(di, int32_t(lowest)), flip);
  for (uint s = begin; s < end; s += uint(L)) {
    const auto dx = hn::Sub(px, hn::LoadU(d, X + s));
    const auto dy = hn::Sub(py, hn::LoadU(d, X + n + s));
    const auto dz = hn::Sub(pz, hn::LoadU(d, X + 2 * n + s));
    const auto dd = hn::Add(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), hn::Mul(dz, dz));
    const auto reach = hn::Add(hn::Add(pr, hn::LoadU(d, X + 3 * n + s)), skin);
    const auto near = hn::Lt(dd, hn::Mul(reach, reach));
    const auto ids = hn::Xor(hn::LoadU(di, reinterpret_cast<const int32_t*>(ID + s)), flip);
    const auto owned = hn::RebindMask(d, hn::Not(hn::Lt(ids, low)));
    const auto pass = hn::And(hn::And(near, owned), hn::FirstN(d, end - s));
    if (hn::AllFalse(d, pass)) continue;
    uint8_t bits[8] = {};
    hn::StoreMaskBits(d, pass, bits);
    uint64_t lanes = 0;
    __builtin_memcpy(&lanes, bits, (L + 7) / 8);
    for (; lanes != 0; lanes &= lanes - 1) {
      const uint j = k.B_sorted[s + uint(__builtin_ctzll(lanes))];
      if (i_fixed && k.is_fixed(j)) continue;
      kk = k.keep_in_row(i, j, k.B_pos[j], x0, x1, c, fill, base, kk, old_begin, old_end);
    }
  }
  return kk;
}

void CountLanes(Kernels& k, uint64_t begin, uint64_t end) {
  Kernels w = k;
  w.row_walk = &WalkRow;
  for (uint64_t i = begin; i < end; ++i) w.k_contact_count(uint(i));
}

}  // namespace repose::gpu::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace repose::gpu {

HWY_EXPORT(FillWalkRows);
HWY_EXPORT(CountLanes);

size_t walk_rows_floats(size_t n) { return 5 * n + HWY_MAX_BYTES / sizeof(float); }

void fill_walk_rows(Kernels& k, uint64_t begin, uint64_t end) { HWY_DYNAMIC_DISPATCH(FillWalkRows)(k, begin, end); }

void contact_count_lanes(Kernels& k, uint64_t begin, uint64_t end) { HWY_DYNAMIC_DISPATCH(CountLanes)(k, begin, end); }

}  // namespace repose::gpu
#endif
