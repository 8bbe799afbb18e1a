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

size_t file_count(const BufferSpec& b, uint32_t n, uint32_t c, uint32_t bodies, uint32_t r) {
  switch (b.count) {
    case BufferCount::Particles: return n;
    case BufferCount::ParticlesPlusOne: return size_t(n) + 1;
    case BufferCount::Bodies: return bodies;
    default: return b.need == BufferNeed::Always ? c : r;
  }
}

}  // namespace

void write_state_file(const std::string& path, const HostState& s, uint64_t step, double time) {
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(kStateMagic, 8);
    put(out, uint32_t(s.pos.size()));
    put(out, uint32_t(s.partner.size()));
    put(out, uint32_t(s.bodies.size()));
    put(out, uint32_t(s.rolling_spring.size()));
    put(out, step);
    put(out, time);
    for_each_file_array(s, [&](const BufferSpec&, const auto& v) { put_array(out, v); });
  }, true);
}

HostState read_state_file(const std::string& path, uint64_t* step, double* time) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read state file '" + path + "'");
  char magic[8];
  in.read(magic, 8);
  bool v2 = in && std::memcmp(magic, kStateMagicV2, 8) == 0;
  if (!in || (!v2 && std::memcmp(magic, kStateMagic, 8) != 0))
    throw std::runtime_error("'" + path + "' is not a Repose state file (bad magic)");
  uint32_t n = 0, c = 0, b = 0, r = 0;
  uint64_t st = 0;
  double t = 0;
  in.read(reinterpret_cast<char*>(&n), 4);
  in.read(reinterpret_cast<char*>(&c), 4);
  in.read(reinterpret_cast<char*>(&b), 4);
  if (!v2) in.read(reinterpret_cast<char*>(&r), 4);
  in.read(reinterpret_cast<char*>(&st), 8);
  in.read(reinterpret_cast<char*>(&t), 8);
  HostState s;
  for_each_file_array(s, [&](const BufferSpec& spec, auto& v) {
    if (v2 && spec.binding == gpu::kBindBodies) {
      // Version 2 bodies are 144 B: the same fields without the trailing drag areas.
      constexpr size_t kV2Body = 144;
      static_assert(sizeof(gpu::Body) > kV2Body);
      std::vector<char> raw(b * kV2Body);
      in.read(raw.data(), std::streamsize(raw.size()));
      s.bodies.assign(b, gpu::Body{});
      for (size_t k = 0; k < b; ++k) std::memcpy(&s.bodies[k], raw.data() + k * kV2Body, kV2Body);
      return;
    }
    v.resize(file_count(spec, n, c, b, r));
    in.read(reinterpret_cast<char*>(v.data()), std::streamsize(v.size() * sizeof(v[0])));
  });
  if (!in) throw std::runtime_error("state file '" + path + "' is truncated");
  if (step) *step = st;
  if (time) *time = t;
  return s;
}

}  // namespace repose
