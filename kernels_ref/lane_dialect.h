// The kernels' dialect in SIMD lanes (Highway, one copy per target: this header is included
// again for each target by the file that includes it, as hwy/foreach_target.h re-includes that
// file): a real is one float per lane, a real3 three, a cond a mask, each operation the IEEE
// operation of the scalar kernel, so shared kernel text (kernels/vector3.h, contact_law.h,
// rigid_body.h) gives the scalar twin's bytes in every lane. With the loads and stores the
// lanes' kernels share (contact_lanes.cpp, body_lanes.cpp).
#if defined(REPOSE_LANE_DIALECT_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef REPOSE_LANE_DIALECT_H_
#undef REPOSE_LANE_DIALECT_H_
#else
#define REPOSE_LANE_DIALECT_H_
#endif

#include <cstring>

#include <hwy/highway.h>

#include "twin_kernels.h"

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

// Field `word` of the structs at indices `index`, each `stride` 4-byte words long.
inline V gather(const void* base, VI index, int stride, int word) {
  VI at = hn::Add(hn::Mul(index, hn::Set(DI(), stride)), hn::Set(DI(), word));
  return hn::GatherIndex(D(), static_cast<const float*>(base), at);
}

// The vec4 rows base[index[l]] of the lanes, as four vectors (x, y, z, w).
struct V4 {
  V x, y, z, w;
  real3 xyz() const { return {x, y, z}; }
};

// ---- Block order: a batch's lanes in the order a transpose within 128-bit blocks leaves them. ----
// Four vectors of consecutive vec4 rows (B = Lanes / 4 rows each, row B j + k in block k of vector
// j) transposed within their blocks (eight interleaves) put row B j + k in lane 4 k + j. hwy's
// LoadInterleaved4 and StoreInterleaved4 add eight shuffles across blocks to keep lane l row l; a
// batch whose lanes load and store consecutive rows in block order skips them, its lane λ being
// row block_order(λ) throughout (the kernels' text works lane by lane: the same bytes).
#if HWY_TARGET != HWY_SCALAR
HWY_INLINE V4 transpose_in_blocks(V a, V b, V c, V e) {
  const D d;
  const V v10_even = hn::InterleaveLower(d, a, c), v10_odd = hn::InterleaveLower(d, b, e);
  const V v32_even = hn::InterleaveUpper(d, a, c), v32_odd = hn::InterleaveUpper(d, b, e);
  return {hn::InterleaveLower(d, v10_even, v10_odd), hn::InterleaveUpper(d, v10_even, v10_odd),
          hn::InterleaveLower(d, v32_even, v32_odd), hn::InterleaveUpper(d, v32_even, v32_odd)};
}
#endif
// log2 of B, the vec4 rows one vector holds: 2, 1 or 0 (AVX-512, AVX2, 128-bit or scalar lanes).
HWY_INLINE int rows_per_vector_log2() {
  static_assert(HWY_LANES(float) <= 16, "block order is written for up to 16 float lanes");
  const size_t L = hn::Lanes(D());
  return L >= 16 ? 2 : L == 8 ? 1 : 0;
}
// The row of a batch in lane λ = 4 k + j (B j + k), for one lane or as a vector of all; and the lane
// of row r (r = B j + k: 4 k + j). With one row per vector (B = 1) both are the identity.
HWY_INLINE size_t block_order(size_t lane) { return ((lane & 3) << rows_per_vector_log2()) + (lane >> 2); }
HWY_INLINE VI block_order(DI di) {
  const VI lane = hn::Iota(di, 0);
  return hn::Add(hn::ShiftLeftSame(hn::And(lane, hn::Set(di, 3)), rows_per_vector_log2()), hn::ShiftRight<2>(lane));
}
HWY_INLINE VI block_order_lane(DI di, VI row) {
  const int b = rows_per_vector_log2();
  return hn::Add(hn::ShiftLeft<2>(hn::And(row, hn::Set(di, (1 << b) - 1))), hn::ShiftRightSame(row, b));
}
// The rows at..at + Lanes - 1, row block_order(λ) in lane λ.
HWY_INLINE V4 load4_block_order(const vec4* at) {
  V4 r;
#if HWY_TARGET == HWY_SCALAR
  hn::LoadInterleaved4(D(), &at->x, r.x, r.y, r.z, r.w);
#else
  const D d;
  const size_t L = hn::Lanes(d);
  const float* f = &at->x;
  r = transpose_in_blocks(hn::LoadU(d, f), hn::LoadU(d, f + L), hn::LoadU(d, f + 2 * L), hn::LoadU(d, f + 3 * L));
#endif
  return r;
}
// Lane λ of r into row at + block_order(λ): load4_block_order's inverse.
HWY_INLINE void store4_block_order(vec4* at, const V4& r) {
#if HWY_TARGET == HWY_SCALAR
  hn::StoreInterleaved4(r.x, r.y, r.z, r.w, D(), &at->x);
#else
  const D d;
  const size_t L = hn::Lanes(d);
  float* f = &at->x;
  const V4 t = transpose_in_blocks(r.x, r.y, r.z, r.w);  // a transpose within blocks is its own inverse
  hn::StoreU(t.x, d, f);
  hn::StoreU(t.y, d, f + L);
  hn::StoreU(t.z, d, f + 2 * L);
  hn::StoreU(t.w, d, f + 3 * L);
#endif
}

#if HWY_TARGET != HWY_SCALAR
// Rows index[4 k + j] of base (index[block_order(4 k + j)] in block order) as the blocks k (four
// floats each) of one vector: 128-bit loads joined in registers.
template <bool kBlockOrder, class DB>
HWY_INLINE hn::Vec<DB> row_blocks(DB d, const vec4* base, const uint* index, size_t j, size_t k0) {
  if constexpr (hn::MaxLanes(DB()) <= 4) {
    const size_t lane = 4 * k0 + j;
    return hn::LoadU(d, &base[index[kBlockOrder ? block_order(lane) : lane]].x);
  } else {
    const hn::Half<DB> dh;
    constexpr size_t half_blocks = hn::MaxLanes(DB()) / 8;
    return hn::Combine(d, row_blocks<kBlockOrder>(dh, base, index, j, k0 + half_blocks),
                       row_blocks<kBlockOrder>(dh, base, index, j, k0));
  }
}
#endif

// Rows base[index[l]] in lane l (base[index[block_order(λ)]] in lane λ in block order): one 128-bit
// load per lane and a transpose in registers, for rows that mostly sit in cache (a body's
// sub-spheres, body_lanes.cpp): copying them through a buffer stalls the wide loads that read it
// back (store forwarding fails), 2.18-2.39 against 1.88-1.95 CPU-s per 400 steps of the stalk
// bucket at rest.
template <bool kBlockOrder = false>
HWY_INLINE V4 rows(const vec4* base, const uint* index) {
#if HWY_TARGET == HWY_SCALAR
  V4 r;
  hn::LoadInterleaved4(D(), &base[index[0]].x, r.x, r.y, r.z, r.w);
  return r;
#else
  const D d;
  return transpose_in_blocks(row_blocks<kBlockOrder>(d, base, index, 0, 0), row_blocks<kBlockOrder>(d, base, index, 1, 0),
                             row_blocks<kBlockOrder>(d, base, index, 2, 0), row_blocks<kBlockOrder>(d, base, index, 3, 0));
#endif
}

// Rows base[index[block_order(λ)]] in lane λ through a buffer, one 16-byte copy per lane, for rows
// that miss the cache (a contact's partners over a bed, contact_lanes.cpp): there the copies'
// loads overlap better than the joins' (the settled 50k bed, 1.59-1.73 against 1.82-1.83 CPU-s per
// 300 steps).
HWY_INLINE V4 rows_via_buffer_block_order(const vec4* base, const uint* index) {
  alignas(64) vec4 buf[HWY_LANES(float)];
  const size_t L = hn::Lanes(D());
  for (size_t l = 0; l < L; ++l) std::memcpy(&buf[l], base + index[l], sizeof(vec4));
  return load4_block_order(buf);
}

// Field `field` (its vec4 row in gpu::Body) of each lane's body b[l], joined in registers.
inline V4 body_rows(const Kernels& k, const uint* b, uint field) {
  static_assert(sizeof(Body) % sizeof(vec4) == 0, "a Body is whole vec4 rows");
  constexpr uint kBodyRow = sizeof(Body) / sizeof(vec4);
  uint at[HWY_LANES(float)];
  for (size_t l = 0; l < hn::Lanes(D()); ++l) at[l] = b[l] * kBodyRow + field;
  return rows(reinterpret_cast<const vec4*>(k.B_bodies), at);
}

// The lanes of mask m (of tag d) as bits, lane 0 the lowest.
template <class DM>
HWY_INLINE uint64_t lane_bits(DM d, hn::Mask<DM> m) {
  uint8_t bits[8] = {};
  hn::StoreMaskBits(d, m, bits);
  uint64_t lanes = 0;
  std::memcpy(&lanes, bits, (hn::Lanes(d) + 7) / 8);
  return lanes;
}

// A vec4 row the same in every lane.
inline V4 same_row(const vec4& r) { return {hn::Set(D(), r.x), hn::Set(D(), r.y), hn::Set(D(), r.z), hn::Set(D(), r.w)}; }

inline void store4(vec4* at, real x, real y, real z, real w) { hn::StoreInterleaved4(x.v, y.v, z.v, w.v, D(), &at->x); }
inline real zero_unless(cond c, real a) { return hn::IfThenElseZero(c.m, a.v); }
inline real3 zero_unless(cond c, real3 a) { return {zero_unless(c, a.x), zero_unless(c, a.y), zero_unless(c, a.z)}; }

}  // namespace repose::gpu::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif
