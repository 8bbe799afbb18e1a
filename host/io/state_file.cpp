#include "io/state_file.h"

#include <cstring>
#include <fstream>
#include <stdexcept>

#include "util/atomic_file.h"

namespace repose {

namespace {

template <class T>
void put(std::ostream& out, const T& v) { out.write(reinterpret_cast<const char*>(&v), sizeof(T)); }

template <class T>
void put_array(std::ostream& out, const std::vector<T>& v) {
  out.write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(T)));
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
    put_array(out, s.pos);
    put_array(out, s.vel);
    put_array(out, s.omega);
    put_array(out, s.force);
    put_array(out, s.torque);
    put_array(out, s.row_start);
    put_array(out, s.partner);
    put_array(out, s.history);
    put_array(out, s.bodies);
    put_array(out, s.rolling_spring);
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
  auto get = [&](auto& v, size_t k) {
    v.resize(k);
    in.read(reinterpret_cast<char*>(v.data()), std::streamsize(k * sizeof(v[0])));
  };
  get(s.pos, n); get(s.vel, n); get(s.omega, n); get(s.force, n); get(s.torque, n);
  get(s.row_start, n + 1); get(s.partner, c); get(s.history, c); get(s.bodies, b);
  get(s.rolling_spring, r);
  if (!in) throw std::runtime_error("state file '" + path + "' is truncated");
  if (step) *step = st;
  if (time) *time = t;
  return s;
}

}  // namespace repose
