#include "engine/particle_order.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <type_traits>

#include "engine/buffer_table.h"
#include "engine/model.h"
#include "util/parallel_each.h"

namespace repose {

ParticleOrder ParticleOrder::identity(uint32_t n) {
  std::vector<uint32_t> ids(n);
  std::iota(ids.begin(), ids.end(), 0u);
  return from_ids(std::move(ids));
}

ParticleOrder ParticleOrder::from_ids(std::vector<uint32_t> id_of) {
  ParticleOrder o;
  o.slot_of.assign(id_of.size(), UINT32_MAX);
  for (size_t s = 0; s < id_of.size(); ++s) {
    if (id_of[s] >= id_of.size() || o.slot_of[id_of[s]] != UINT32_MAX)
      throw std::invalid_argument("a particle order must hold every global id once");
    o.slot_of[id_of[s]] = uint32_t(s);
  }
  o.id_of = std::move(id_of);
  return o;
}

bool ParticleOrder::is_identity() const {
  for (size_t s = 0; s < id_of.size(); ++s)
    if (id_of[s] != s) return false;
  return true;
}

std::vector<uint32_t> ParticleOrder::table() const {
  std::vector<uint32_t> t = id_of;
  t.insert(t.end(), slot_of.begin(), slot_of.end());
  return t;
}

ParticleOrder cell_order(const std::vector<gpu::vec4>& pos, const std::vector<gpu::Body>& bodies, double cell,
                         unsigned threads) {
  return cell_order(pos, {}, bodies, cell, threads);
}

namespace {

constexpr size_t kBlock = size_t(1) << 16;

// body(begin, end) over [0, n) in blocks of kBlock, on up to `threads` threads: a million
// particles' rows and their contact list's move on all the host's cores, a small state on the
// caller's thread alone (one block).
template <class Body>
void for_blocks(size_t n, unsigned threads, Body body) {
  parallel_each((n + kBlock - 1) / kBlock, threads,
                [&](size_t b) { body(b * kBlock, std::min(n, (b + 1) * kBlock)); });
}

// The lowest corner of the positions, each block's on its own thread (a minimum in any order).
std::array<double, 3> lowest_corner(const std::vector<gpu::vec4>& pos, unsigned threads) {
  std::vector<std::array<double, 3>> lo((pos.size() + kBlock - 1) / kBlock, {HUGE_VAL, HUGE_VAL, HUGE_VAL});
  for_blocks(pos.size(), threads, [&](size_t begin, size_t end) {
    std::array<double, 3>& l = lo[begin / kBlock];
    for (size_t r = begin; r < end; ++r) {
      l[0] = std::min(l[0], double(pos[r].x));
      l[1] = std::min(l[1], double(pos[r].y));
      l[2] = std::min(l[2], double(pos[r].z));
    }
  });
  std::array<double, 3> corner{HUGE_VAL, HUGE_VAL, HUGE_VAL};
  for (const auto& l : lo)
    for (int k = 0; k < 3; ++k) corner[k] = std::min(corner[k], l[k]);
  return corner;
}

}  // namespace

// A renewal of a million grains' order on a GPU's host: the keys and their sort were ~25 ms of
// one thread (a 1e6 bed, this project's machine), now on every host core.
ParticleOrder cell_order(const std::vector<gpu::vec4>& pos, const std::vector<uint32_t>& id_of_row,
                         const std::vector<gpu::Body>& bodies, double cell, unsigned threads) {
  const std::array<double, 3> lo = lowest_corner(pos, threads);
  auto axis = [&](float x, int k) {
    double c = std::floor((double(x) - lo[k]) / cell);
    return uint64_t(std::clamp(c, 0.0, double(0x1fffff)));
  };
  auto key = [&](const gpu::vec4& p) { return axis(p.z, 2) << 42 | axis(p.y, 1) << 21 | axis(p.x, 0); };
  std::vector<uint32_t> ids(pos.size());
  if (bodies.empty()) {  // (cell, global id): no two alike, so any sort gives this order
    std::vector<std::pair<uint64_t, uint32_t>> keys(pos.size());
    for_blocks(pos.size(), threads, [&](size_t begin, size_t end) {
      for (size_t r = begin; r < end; ++r) keys[r] = {key(pos[r]), id_of_row.empty() ? uint32_t(r) : id_of_row[r]};
    });
    parallel_sort(keys, threads);
    for (size_t s = 0; s < keys.size(); ++s) ids[s] = keys[s].second;
    return ParticleOrder::from_ids(std::move(ids));
  }
  std::vector<std::pair<uint64_t, uint32_t>> keys(bodies.size());
  for (size_t b = 0; b < bodies.size(); ++b) keys[b] = {key(bodies[b].pos), uint32_t(b)};
  std::sort(keys.begin(), keys.end());
  size_t s = 0;
  for (const auto& k : keys) {
    const gpu::uvec4& range = bodies[k.second].spheres;
    for (uint32_t g = range.x; g < range.x + range.y && s < ids.size(); ++g) ids[s++] = g;
  }
  return ParticleOrder::from_ids(std::move(ids));
}

namespace {

// A compressed-row list whose rows move, new row r being old row old_of_new[r], each keeping its
// entries in their order: `start` becomes the moved rows' starts; returns each old entry's new index.
std::vector<uint32_t> move_rows(std::vector<uint32_t>& start, const std::vector<uint32_t>& old_of_new,
                                unsigned threads) {
  size_t n = old_of_new.size();
  std::vector<uint32_t> new_of_old_entry(start.size() == n + 1 ? start[n] : 0u);
  std::vector<uint32_t> new_start(n + 1, 0u);
  for (size_t r = 0; r < n; ++r) new_start[r + 1] = new_start[r] + (start[old_of_new[r] + 1] - start[old_of_new[r]]);
  for_blocks(n, threads, [&](size_t begin, size_t end) {
    for (size_t r = begin; r < end; ++r) {
      uint32_t o = old_of_new[r], next = new_start[r];
      for (uint32_t e = start[o]; e < start[o + 1]; ++e) new_of_old_entry[e] = next++;
    }
  });
  start = std::move(new_start);
  return new_of_old_entry;
}

// One row's room, reused by every row of a conversion: a fresh vector per row would leave the
// allocator holding freed rows (glibc keeps blocks under its mmap threshold, which grows to the
// 16 MB of a particle row at 1e6 spheres): +36 B per sphere resident while stepping.
class RowScratch {
 public:
  explicit RowScratch(size_t bytes) : room_(std::make_unique_for_overwrite<std::byte[]>(bytes)), bytes_(bytes) {}
  template <class T>
  T* room(size_t n) {
    if (n * sizeof(T) > bytes_) throw std::logic_error("a kept row is larger than the conversion's scratch");
    return reinterpret_cast<T*>(room_.get());  // bytes from new[] hold any trivially copyable row
  }

 private:
  std::unique_ptr<std::byte[]> room_;
  size_t bytes_;
};

// v[r] = old v[from[r]] for every r, through the scratch: a conversion holds one row twice, never
// the whole state (engine/memory_need.cpp). A cycle walk in place would need no scratch, but it
// chases the permutation one dependent load at a time: 3x slower than these copies over the 50k
// bed's state (0.25 against 0.09 ms per step).
template <class T>
void gather_row(std::vector<T>& v, const std::vector<uint32_t>& from, RowScratch& scratch, unsigned threads) {
  if (v.empty()) return;
  if (v.size() != from.size()) throw std::logic_error("a kept row does not fit its particles");
  T* out = scratch.room<T>(v.size());
  for_blocks(v.size(), threads, [&](size_t begin, size_t end) {
    for (size_t r = begin; r < end; ++r) out[r] = v[from[r]];
  });
  for_blocks(v.size(), threads, [&](size_t begin, size_t end) {
    std::memcpy(v.data() + begin, out + begin, (end - begin) * sizeof(T));
  });
}

// v[to[k]] = old v[k] for every k, as gather_row (`to` is a permutation: no two blocks write one entry).
template <class T>
void scatter_row(std::vector<T>& v, const std::vector<uint32_t>& to, RowScratch& scratch, unsigned threads) {
  if (v.empty()) return;
  if (v.size() != to.size()) throw std::logic_error("a kept row does not fit its contact list");
  T* out = scratch.room<T>(v.size());
  for_blocks(v.size(), threads, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) out[to[k]] = v[k];
  });
  for_blocks(v.size(), threads, [&](size_t begin, size_t end) {
    std::memcpy(v.data() + begin, out + begin, (end - begin) * sizeof(T));
  });
}

// Every index x in v becomes map[x] (those at or above `below`, a wall's, stay).
void renumber(std::vector<uint32_t>& v, const std::vector<uint32_t>& map, uint32_t below, unsigned threads) {
  for_blocks(v.size(), threads, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k)
      if (v[k] < below) v[k] = map[v[k]];
  });
}

// The bytes of the largest row of `s` that moves.
size_t largest_row_bytes(HostState& s) {
  size_t bytes = 0;
  for_each_kept(s, [&](const BufferSpec&, auto& v) { bytes = std::max(bytes, v.size() * sizeof(v[0])); });
  return bytes;
}

// Moves every particle of `s` from its index to new_of_old[index] (old_of_new its inverse), a row
// at a time: per-particle rows, the rows of both contact lists, and the particle indices in them.
// Returns each old contact's new index.
std::vector<uint32_t> move_particles(HostState& s, const std::vector<uint32_t>& old_of_new,
                                     const std::vector<uint32_t>& new_of_old, unsigned threads) {
  RowScratch scratch(largest_row_bytes(s));
  {  // gone before contact_to comes: one entry map at a time (engine/memory_need.cpp)
    std::vector<uint32_t> trans_to = move_rows(s.trans_start, old_of_new, threads);
    scatter_row(s.trans_list, trans_to, scratch, threads);
  }
  std::vector<uint32_t> contact_to = move_rows(s.row_start, old_of_new, threads);
  for_each_kept(s, [&](const BufferSpec& b, auto& v) {
    if (b.count == BufferCount::Particles) gather_row(v, old_of_new, scratch, threads);
    if (b.count == BufferCount::Contacts || b.count == BufferCount::ContactsTwice)
      scatter_row(v, contact_to, scratch, threads);
  });
  constexpr uint32_t kAll = ~0u;
  renumber(s.trans_list, contact_to, kAll, threads);
  renumber(s.partner, new_of_old, uint32_t(old_of_new.size()), threads);  // N + w: wall w
  renumber(s.owner, new_of_old, kAll, threads);
  return contact_to;
}

}  // namespace

void to_stored(HostState& state, const ParticleOrder& order, unsigned threads) {
  if (!order.is_identity()) move_particles(state, order.id_of, order.slot_of, threads);
}

void to_global(HostState& state, const ParticleOrder& order, unsigned threads) {
  if (!order.is_identity()) move_particles(state, order.slot_of, order.id_of, threads);
}

void to_other_slots(HostState& state, const ParticleOrder& from, const ParticleOrder& to, unsigned threads) {
  size_t n = to.size();
  if (from.size() != n) throw std::invalid_argument("to_other_slots: orders of different numbers of particles");
  std::vector<uint32_t> old_of_new(n), new_of_old(n);
  for (size_t s = 0; s < n; ++s) {
    old_of_new[s] = from.slot_of[to.id_of[s]];
    new_of_old[s] = to.slot_of[from.id_of[s]];
  }
  move_particles(state, old_of_new, new_of_old, threads);
}

std::vector<uint32_t> stored_contact_ids(const HostState& global, const ParticleOrder& order) {
  std::vector<uint32_t> ids;
  if (global.row_start.size() != order.size() + 1) return ids;
  ids.reserve(global.row_start.back());
  for (uint32_t g : order.id_of)
    for (uint32_t c = global.row_start[g]; c < global.row_start[g + 1]; ++c) ids.push_back(c);
  return ids;
}

ConstantData stored_constants(const Model& m, const ParticleOrder& order) {
  auto stored = [&](const auto& by_id) {
    auto v = by_id;
    for (size_t s = 0; s < v.size() && s < order.size(); ++s) v[s] = by_id[order.id_of[s]];
    return v;
  };
  ConstantData c;
  c.material = stored(m.material);
  c.pairs = m.pairs;
  c.subs = stored(m.subs);
  c.parts = m.parts;
  c.wall_grid = m.wall_grid;
  c.ids = order.table();
  return c;
}

}  // namespace repose
