#include "engine/particle_order.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <type_traits>

#include "engine/buffer_table.h"
#include "engine/model.h"

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

ParticleOrder cell_order(const std::vector<gpu::vec4>& pos, double cell) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
  for (const gpu::vec4& p : pos) {
    lo[0] = std::min(lo[0], double(p.x));
    lo[1] = std::min(lo[1], double(p.y));
    lo[2] = std::min(lo[2], double(p.z));
  }
  auto axis = [&](float x, int k) {
    double c = std::floor((double(x) - lo[k]) / cell);
    return uint64_t(std::clamp(c, 0.0, double(0x1fffff)));
  };
  std::vector<std::pair<uint64_t, uint32_t>> keys(pos.size());
  for (size_t g = 0; g < pos.size(); ++g) {
    const gpu::vec4& p = pos[g];
    keys[g] = {axis(p.z, 2) << 42 | axis(p.y, 1) << 21 | axis(p.x, 0), uint32_t(g)};
  }
  std::sort(keys.begin(), keys.end());
  std::vector<uint32_t> ids(pos.size());
  for (size_t s = 0; s < keys.size(); ++s) ids[s] = keys[s].second;
  return ParticleOrder::from_ids(std::move(ids));
}

namespace {

// A compressed-row list whose rows move, new row r being old row old_of_new[r], each keeping its
// entries in their order: the moved rows' starts, and each old entry's new index.
void move_rows(const std::vector<uint32_t>& start, const std::vector<uint32_t>& old_of_new,
               std::vector<uint32_t>& new_start, std::vector<uint32_t>& new_of_old_entry) {
  size_t n = old_of_new.size();
  new_start.assign(n + 1, 0u);
  new_of_old_entry.assign(start.size() == n + 1 ? start[n] : 0u, 0u);
  uint32_t next = 0;
  for (size_t r = 0; r < n; ++r) {
    new_start[r] = next;
    uint32_t o = old_of_new[r];
    for (uint32_t e = start[o]; e < start[o + 1]; ++e) new_of_old_entry[e] = next++;
  }
  new_start[n] = next;
}

// v with old entry k moved to new_of_old[k].
template <class T>
std::vector<T> scattered(const std::vector<T>& v, const std::vector<uint32_t>& new_of_old) {
  if (v.size() != new_of_old.size()) throw std::logic_error("a kept row does not fit its contact list");
  std::vector<T> out(v.size());
  for (size_t k = 0; k < v.size(); ++k) out[new_of_old[k]] = v[k];
  return out;
}

// The state with every particle moved from its index to new_of_old[index] (old_of_new its
// inverse): per-particle rows, the rows of both contact lists, and the particle indices in them.
HostState moved_state(HostState out, const std::vector<uint32_t>& old_of_new,
                      const std::vector<uint32_t>& new_of_old, std::vector<uint32_t>* contact_of) {
  std::vector<uint32_t> contact_to, trans_to, row_start, trans_start;
  move_rows(out.row_start, old_of_new, row_start, contact_to);
  move_rows(out.trans_start, old_of_new, trans_start, trans_to);
  out.row_start = std::move(row_start);
  out.trans_start = std::move(trans_start);
  for_each_kept(out, [&](const BufferSpec& b, auto& v) {
    using T = typename std::decay_t<decltype(v)>::value_type;
    if (b.count == BufferCount::Particles && !v.empty()) {
      std::vector<T> old = std::move(v);
      v.resize(old.size());
      for (size_t r = 0; r < v.size(); ++r) v[r] = old[old_of_new[r]];
    } else if ((b.count == BufferCount::Contacts || b.count == BufferCount::ContactsTwice) && !v.empty()) {
      v = scattered(v, contact_to);
    }
  });
  out.trans_list = scattered(out.trans_list, trans_to);
  for (uint32_t& c : out.trans_list) c = contact_to[c];
  uint32_t n = uint32_t(old_of_new.size());
  for (uint32_t& p : out.partner)
    if (p < n) p = new_of_old[p];
  for (uint32_t& i : out.owner) i = new_of_old[i];
  if (contact_of) *contact_of = std::move(contact_to);
  return out;
}

}  // namespace

HostState stored_state(const HostState& global, const ParticleOrder& order, std::vector<uint32_t>* contact_of) {
  if (contact_of) contact_of->clear();
  if (order.is_identity()) return global;
  std::vector<uint32_t> stored_of;  // each global contact's stored index
  HostState stored = moved_state(global, order.id_of, order.slot_of, &stored_of);
  if (contact_of) {
    contact_of->resize(stored_of.size());
    for (size_t c = 0; c < stored_of.size(); ++c) (*contact_of)[stored_of[c]] = uint32_t(c);
  }
  return stored;
}

HostState global_state(HostState stored, const ParticleOrder& order, std::vector<uint32_t>* contact_of) {
  if (contact_of) contact_of->clear();
  if (order.is_identity()) return stored;
  return moved_state(std::move(stored), order.slot_of, order.id_of, contact_of);
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
  c.ids = order.table();
  return c;
}

}  // namespace repose
