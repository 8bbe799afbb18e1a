#include "engine/buffer_table.h"

#include <algorithm>

namespace repose {

size_t buffer_elements(const BufferSpec& b, const Layout& l) {
  bool needed = b.need == BufferNeed::Always || b.need == BufferNeed::Alias ||
                (b.need == BufferNeed::FullEntries && !l.lean_contacts) ||
                (b.need == BufferNeed::Bodies && l.n_bodies > 0) ||
                (b.need == BufferNeed::RollingSprings && l.rolling_springs);
  if (!needed) return 0;
  size_t n = l.n_particles, c = l.capacity, t = l.table_size;
  switch (b.count) {
    case BufferCount::Particles: return n;
    case BufferCount::ParticlesPlusOne: return n + 1;
    case BufferCount::ParticlesTwice: return 2 * n;
    case BufferCount::Contacts: return c;
    case BufferCount::ContactsTwice: return 2 * c;
    case BufferCount::Transposed: return c;
    case BufferCount::Buckets: return t + 1;
    case BufferCount::BucketsPlusOne: return t + 2;
    case BufferCount::Pairs: return size_t(l.n_materials) * l.n_materials;
    case BufferCount::WallRows: return l.n_walls + size_t(l.batch_steps) * l.n_moving_walls;
    case BufferCount::WallSums: return 3 * size_t(l.n_wall_groups);
    case BufferCount::Bodies: return l.n_bodies;
    case BufferCount::Control: return gpu::kControlWords;
    case BufferCount::CandidateSlots: return n * gpu::kCandidateSlots;
    case BufferCount::Parts: return l.n_parts;
    case BufferCount::ScanBlocks: return size_t(gpu::scan_blocks_for(uint32_t(std::max(n, t + 1)))) + 1;
    case BufferCount::WallGrid: return l.wall_grid_words;
  }
  return 0;
}

size_t binding_bytes(uint32_t binding, const Layout& l) {
  size_t bytes = 0;
  for (const BufferSpec& b : kBufferTable)
    if (b.binding == binding) bytes = std::max(bytes, buffer_elements(b, l) * b.element_bytes);
  return bytes;
}

size_t used_elements(const BufferSpec& b, const Layout& l, const HostState& s) {
  size_t all = buffer_elements(b, l);
  if (b.count == BufferCount::Contacts || b.count == BufferCount::ContactsTwice)
    return std::min<size_t>(all ? s.control.at(gpu::kCtlContacts) : 0, l.capacity);
  if (b.count == BufferCount::Transposed) return std::min<size_t>(s.trans_start.at(l.n_particles), l.capacity);
  return all;
}

size_t bytes_per_contact(const Layout& l) {
  Layout one = l;
  one.capacity = 1;
  size_t bytes = 0;
  for (const BufferSpec& b : kBufferTable)
    if (!b.alias() &&
        (b.count == BufferCount::Contacts || b.count == BufferCount::ContactsTwice || b.count == BufferCount::Transposed))
      bytes += buffer_elements(b, one) * b.element_bytes;
  return bytes;
}

}  // namespace repose
