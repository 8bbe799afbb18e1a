#include "io/state_file.h"

#include <cstring>
#include <fstream>
#include <stdexcept>

#include "engine/buffer_table.h"
#include "util/atomic_file.h"

namespace repose {

namespace {

template <class T>
void put(std::ostream& out, const T& v) { out.write(reinterpret_cast<const char*>(&v), sizeof(T)); }

template <class T>
void put_array(std::ostream& out, const std::vector<T>& v) {
  out.write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(T)));
}

// The File rows of the buffer table, in binding order, each with its count from the header:
// particles N (N + 1 for row starts), contacts C, bodies B, and R for contact state that only
// some cases keep (the rolling springs). A new row of another shape needs a new format version.
template <class State, class F>
void for_each_file_array(State& s, F&& f) {
  for_each_kept(s, [&](const BufferSpec& b, auto& v) {
    if (b.keep == BufferKeep::File) f(b, v);
  });
}

// The State rows, in binding order: what a restart needs beside the File rows.
template <class State, class F>
void for_each_restart_array(State& s, F&& f) {
  for_each_kept(s, [&](const BufferSpec& b, auto& v) {
    if (b.keep == BufferKeep::State) f(b, v);
  });
}

// Elements of a State row a state file holds: all of it, of the control words the first few.
size_t restart_count(const BufferSpec& b, size_t size) {
  return b.count == BufferCount::Control ? kRestartControlWords : size;
}

size_t file_count(const BufferSpec& b, uint32_t n, uint32_t c, uint32_t bodies, uint32_t r) {
  switch (b.count) {
    case BufferCount::Particles: return n;
    case BufferCount::ParticlesPlusOne: return size_t(n) + 1;
    case BufferCount::Bodies: return bodies;
    default: return b.need == BufferNeed::Always ? c : r;
  }
}


int version_of(const char magic[8]) {
  if (std::memcmp(magic, kStateMagic, 8) == 0) return 4;
  if (std::memcmp(magic, kStateMagicV3, 8) == 0) return 3;
  if (std::memcmp(magic, kStateMagicV2, 8) == 0) return 2;
  return 0;
}

}  // namespace

void write_state_file(const std::string& path, const HostState& s, uint64_t step, double time) {
  if (s.control.size() < kRestartControlWords || s.pos_at_build.size() != s.pos.size() ||
      s.owner.size() != s.partner.size() || s.trans_start.size() != s.pos.size() + 1 ||
      s.trans_list.size() != s.trans_start.back())
    throw std::logic_error("write_state_file: the host state lacks the neighbour-list bookkeeping");
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(kStateMagic, 8);
    put(out, uint32_t(s.pos.size()));
    put(out, uint32_t(s.partner.size()));
    put(out, uint32_t(s.bodies.size()));
    put(out, uint32_t(s.rolling_spring.size()));
    put(out, step);
    put(out, time);
    for_each_file_array(s, [&](const BufferSpec&, const auto& v) { put_array(out, v); });
    // Version 4: the neighbour list's bookkeeping (the State rows, in table order), so a restart
    // continues with the same bytes; of the control words the first kRestartControlWords.
    for_each_restart_array(s, [&](const BufferSpec& b, const auto& v) {
      out.write(reinterpret_cast<const char*>(v.data()), std::streamsize(restart_count(b, v.size()) * sizeof(v[0])));
    });
  }, true);
}

HostState read_state_file(const std::string& path, StateFileInfo& info) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read state file '" + path + "'");
  char magic[8];
  in.read(magic, 8);
  int version = in ? version_of(magic) : 0;
  if (!version) throw std::runtime_error("'" + path + "' is not a Repose state file (bad magic)");
  uint32_t n = 0, c = 0, b = 0, r = 0;
  in.read(reinterpret_cast<char*>(&n), 4);
  in.read(reinterpret_cast<char*>(&c), 4);
  in.read(reinterpret_cast<char*>(&b), 4);
  if (version >= 3) in.read(reinterpret_cast<char*>(&r), 4);
  in.read(reinterpret_cast<char*>(&info.step), 8);
  in.read(reinterpret_cast<char*>(&info.time), 8);
  info.version = version;
  // Counts come from the file: refuse absurd ones before allocating (a damaged header).
  if (!in || n > (1u << 30) || c > (1u << 30) || b > n || (r != 0 && r != c))
    throw std::runtime_error("state file '" + path + "' has a damaged header");
  HostState s;
  auto get = [&](auto& v, size_t k) {
    v.resize(k);
    in.read(reinterpret_cast<char*>(v.data()), std::streamsize(k * sizeof(v[0])));
  };
  for_each_file_array(s, [&](const BufferSpec& spec, auto& v) {
    if (version == 2 && spec.binding == gpu::kBindBodies) {
      // Version 2 bodies are 144 B: the same fields without the trailing drag areas.
      constexpr size_t kV2Body = 144;
      static_assert(sizeof(gpu::Body) > kV2Body);
      std::vector<char> raw(b * kV2Body);
      in.read(raw.data(), std::streamsize(raw.size()));
      s.bodies.assign(b, gpu::Body{});
      for (size_t k = 0; k < b; ++k) std::memcpy(&s.bodies[k], raw.data() + k * kV2Body, kV2Body);
      return;
    }
    get(v, file_count(spec, n, c, b, r));
  });
  if (version >= 4) {
    for_each_restart_array(s, [&](const BufferSpec& spec, auto& v) {
      if (spec.count == BufferCount::Control) {
        v.assign(gpu::kControlWords, {});
        in.read(reinterpret_cast<char*>(v.data()), kRestartControlWords * sizeof(v[0]));
        return;
      }
      if (spec.count == BufferCount::Transposed && in && s.trans_start[n] > c)
        throw std::runtime_error("state file '" + path + "' is damaged");
      get(v, spec.count == BufferCount::Transposed ? (in ? s.trans_start[n] : 0)  // trans_start came before
                                                    : file_count(spec, n, c, b, r));
    });
  }
  if (!in) throw std::runtime_error("state file '" + path + "' is truncated");
  return s;
}

HostState read_state_file(const std::string& path, uint64_t* step, double* time) {
  StateFileInfo info;
  HostState s = read_state_file(path, info);
  if (step) *step = info.step;
  if (time) *time = info.time;
  return s;
}

}  // namespace repose
