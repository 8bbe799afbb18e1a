#include "io/state_file.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>

#include "engine/buffer_table.h"
#include "io/state_validation.h"
#include "util/atomic_file.h"
#include "util/hash.h"
#include "util/input_error.h"
#include "util/input_file.h"

#define XXH_INLINE_ALL  // xxhash.h's functions compiled here: no library to link or bundle
#include <xxhash.h>

namespace repose {

namespace {

constexpr int kFirstXxh3Version = 6;  // FNV-1a before it (io/state_file.h)

// The checksum of a restartable version, fed in pieces (state_checksum).
class Checksum {
 public:
  explicit Checksum(int version) : fnv_(version < kFirstXxh3Version) {
    if (!fnv_) XXH3_64bits_reset(&xxh_);
  }
  void add(const void* data, size_t bytes) {
    if (fnv_) fnv1a_.add(data, bytes);
    else XXH3_64bits_update(&xxh_, data, bytes);
  }
  uint64_t value() const { return fnv_ ? fnv1a_.value() : XXH3_64bits_digest(&xxh_); }

 private:
  bool fnv_;
  Fnv1a fnv1a_;
  XXH3_state_t xxh_;
};

// The File rows of the buffer table, in binding order, each with its count from the header:
// particles N (N + 1 for row starts), contacts C, bodies B, and R for contact state that only
// some cases keep (the rolling springs). A new row of another shape needs a new format version.
template <class State, class F>
void for_each_file_array(State& s, F&& f) {
  for_each_kept(s, [&](const BufferSpec& b, auto& v) {
    if (b.keep == BufferKeep::File) f(b, v);
  });
}

// The State rows, in binding order: what a restart needs beside the File rows (version 4 on). The
// transposed list, whose length is trans_start[N] (a row before it), is the last.
template <class State, class F>
void for_each_restart_array(State& s, F&& f) {
  for_each_kept(s, [&](const BufferSpec& b, auto& v) {
    if (b.keep == BufferKeep::State) f(b, v);
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

// Elements of a State row other than the transposed list that a state file holds: of the control
// words the first kRestartControlWords.
size_t restart_count(const BufferSpec& b, uint32_t n, uint32_t c, uint32_t bodies, uint32_t r) {
  return b.count == BufferCount::Control ? kRestartControlWords : file_count(b, n, c, bodies, r);
}

constexpr uint64_t kChecksumBytes = 8;

int version_of(const char magic[8]) {
  for (auto [version, m] : {std::pair{6, kStateMagic}, {5, kStateMagicV5}, {4, kStateMagicV4}, {3, kStateMagicV3}, {2, kStateMagicV2}})
    if (std::memcmp(magic, m, 8) == 0) return version;
  return 0;
}

constexpr size_t kV2Body = 144;  // version 2 bodies: the same fields without the trailing drag areas
static_assert(sizeof(gpu::Body) > kV2Body);

struct Header {
  int version = 0;
  uint32_t n = 0, c = 0, b = 0, r = 0;
};

// Bytes of a file of this header, without the transposed list (whose length is in the file) and
// the checksum.
uint64_t fixed_bytes(const Header& h) {
  uint64_t bytes = 8 + 4 * (h.version >= 3 ? 4 : 3) + 16 + (restartable_state_version(h.version) ? kStateCaseHashBytes : 0);
  HostState none;
  for_each_file_array(none, [&](const BufferSpec& spec, const auto&) {
    size_t element = h.version == 2 && spec.binding == gpu::kBindBodies ? kV2Body : spec.element_bytes;
    bytes += uint64_t(file_count(spec, h.n, h.c, h.b, h.r)) * element;
  });
  if (h.version < 4) return bytes;
  for_each_restart_array(none, [&](const BufferSpec& spec, const auto&) {
    if (spec.count != BufferCount::Transposed) bytes += uint64_t(restart_count(spec, h.n, h.c, h.b, h.r)) * spec.element_bytes;
  });
  return bytes;
}

// Reads a state file front to back, hashing what it reads; every read is checked against the
// bytes the file has left, so a damaged count never allocates more than the file holds.
class StateReader {
 public:
  explicit StateReader(const std::string& path) : path_(path), in_(path, std::ios::binary) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) fail("no such state file");
    if (auto why = why_not_input_file(path, ~uintmax_t(0)); !why.empty())
      fail(why + ": give a state file (--state-out, or DIR/checkpoint.state)");
    left_ = std::filesystem::file_size(path, ec);
    if (!in_ || ec) fail("cannot read the state file");
  }
  [[noreturn]] void fail(const std::string& what) const { throw InputError(path_, 0, 0, what); }
  uint64_t left() const { return left_; }
  void raw(void* data, uint64_t bytes) {
    if (bytes > left_) fail("truncated: " + std::to_string(left_) + " bytes left where " + std::to_string(bytes) + " are needed");
    in_.read(static_cast<char*>(data), std::streamsize(bytes));
    if (!in_) fail("cannot read the state file");
    if (sum_) sum_->add(data, bytes);
    left_ -= bytes;
  }
  // From here on, and `first` read before, hashed by `version`'s checksum.
  void start_checksum(int version, const void* first, uint64_t bytes) {
    sum_.emplace(version);
    sum_->add(first, bytes);
  }
  template <class T>
  void value(T& v) { raw(&v, sizeof v); }
  template <class T>
  void array(std::vector<T>& v, uint64_t count) {
    if (count > left_ / sizeof(T))
      fail("truncated: " + std::to_string(left_) + " bytes left for " + std::to_string(count) + " entries");
    v.resize(count);
    raw(v.data(), count * sizeof(T));
  }
  uint64_t hash() const { return sum_ ? sum_->value() : 0; }

 private:
  std::string path_;
  std::ifstream in_;
  uint64_t left_ = 0;
  std::optional<Checksum> sum_;  // in a file of a restartable version
};

Header read_header(StateReader& in, StateFileInfo& info) {
  Header h;
  char magic[8] = {0};
  if (in.left() < 8) in.fail("not a Repose state file (" + std::to_string(in.left()) + " bytes)");
  in.raw(magic, 8);
  h.version = version_of(magic);
  if (!h.version) in.fail("not a Repose state file (bad magic)");
  if (restartable_state_version(h.version)) in.start_checksum(h.version, magic, sizeof magic);
  in.value(h.n);
  in.value(h.c);
  in.value(h.b);
  if (h.version >= 3) in.value(h.r);
  in.value(info.step);
  in.value(info.time);
  info.version = h.version;
  if (restartable_state_version(h.version)) {
    char hash[kStateCaseHashBytes];
    in.raw(hash, sizeof hash);
    info.case_hash = hash[0] ? std::string(hash, sizeof hash) : "";
  }
  if (h.n > (1u << 30) || h.c > (1u << 30) || h.b > h.n || (h.r != 0 && h.r != h.c))
    in.fail("damaged header (" + std::to_string(h.n) + " particles, " + std::to_string(h.c) + " contacts, " +
            std::to_string(h.b) + " bodies, " + std::to_string(h.r) + " rolling springs)");
  return h;
}

// The file's length must be what its header announces: nothing missing, nothing appended.
void check_length(StateReader& in, const Header& h, uint64_t file_bytes) {
  uint64_t fixed = fixed_bytes(h), tail = restartable_state_version(h.version) ? kChecksumBytes : 0;
  bool fits = h.version >= 4 ? file_bytes >= fixed + tail && (file_bytes - fixed - tail) % 4 == 0 &&
                                   (file_bytes - fixed - tail) / 4 <= h.c
                             : file_bytes == fixed;
  if (!fits)
    in.fail("is " + std::to_string(file_bytes) + " bytes, but its header (" + std::to_string(h.n) + " particles, " +
            std::to_string(h.c) + " contacts, " + std::to_string(h.b) + " bodies) needs " + std::to_string(fixed + tail) +
            (h.version >= 4 ? " + 4 per transposed contact" : "") + ": truncated, or bytes appended");
}

void read_arrays(StateReader& in, const Header& h, uint64_t file_bytes, HostState& s) {
  for_each_file_array(s, [&](const BufferSpec& spec, auto& v) {
    if (h.version == 2 && spec.binding == gpu::kBindBodies) {
      std::vector<char> raw;
      in.array(raw, uint64_t(h.b) * kV2Body);
      s.bodies.assign(h.b, gpu::Body{});
      for (size_t k = 0; k < h.b; ++k) std::memcpy(&s.bodies[k], raw.data() + k * kV2Body, kV2Body);
      return;
    }
    in.array(v, file_count(spec, h.n, h.c, h.b, h.r));
  });
  if (h.version < 4) return;
  for_each_restart_array(s, [&](const BufferSpec& spec, auto& v) {
    if (spec.count == BufferCount::Control) {
      v.assign(gpu::kControlWords, {});
      in.raw(v.data(), kRestartControlWords * sizeof(v[0]));
    } else if (spec.count == BufferCount::Transposed) {
      uint64_t tail = restartable_state_version(h.version) ? kChecksumBytes : 0, transposed = (in.left() - tail) / sizeof(v[0]);
      if (s.trans_start[h.n] != transposed)
        in.fail("is " + std::to_string(file_bytes) + " bytes, but its header and trans_start[N] = " +
                std::to_string(s.trans_start[h.n]) + " need " +
                std::to_string(file_bytes - 4 * transposed + 4ull * s.trans_start[h.n]) + ": truncated, or bytes appended");
      in.array(v, transposed);
    } else {
      in.array(v, restart_count(spec, h.n, h.c, h.b, h.r));
    }
  });
}

}  // namespace

uint64_t state_checksum(int version, const void* data, size_t bytes) {
  Checksum sum(version);
  sum.add(data, bytes);
  return sum.value();
}

void write_state_file(const std::string& path, const HostState& s, uint64_t step, double time,
                      const std::string& case_hash) {
  if (s.control.size() < kRestartControlWords || s.pos_at_build.size() != s.pos.size() ||
      s.owner.size() != s.partner.size() || s.trans_start.size() != s.pos.size() + 1 ||
      s.trans_list.size() != s.trans_start.back())
    throw std::logic_error("write_state_file: the host state lacks the neighbour-list bookkeeping");
  char hash_field[kStateCaseHashBytes] = {0};
  std::memcpy(hash_field, case_hash.data(), std::min(case_hash.size(), sizeof hash_field));
  write_file_atomically(path, [&](std::ostream& out) {
    Checksum sum(kStateVersion);
    auto put = [&](const void* data, size_t bytes) {
      out.write(static_cast<const char*>(data), std::streamsize(bytes));
      sum.add(data, bytes);
    };
    auto put_array = [&](const auto& v) { put(v.data(), v.size() * sizeof(v[0])); };
    uint32_t counts[4] = {uint32_t(s.pos.size()), uint32_t(s.partner.size()), uint32_t(s.bodies.size()),
                          uint32_t(s.rolling_spring.size())};
    put(kStateMagic, 8);
    put(counts, sizeof counts);
    put(&step, 8);
    put(&time, 8);
    put(hash_field, sizeof hash_field);
    for_each_file_array(s, [&](const BufferSpec&, const auto& v) { put_array(v); });
    // The neighbour list's bookkeeping (the State rows, in table order), so a restart continues
    // with the same bytes; of the control words the first kRestartControlWords.
    for_each_restart_array(s, [&](const BufferSpec& b, const auto& v) {
      put(v.data(), (b.count == BufferCount::Control ? kRestartControlWords : v.size()) * sizeof(v[0]));
    });
    uint64_t checksum = sum.value();
    out.write(reinterpret_cast<const char*>(&checksum), 8);
  }, true);
}

HostState read_state_file(const std::string& path, StateFileInfo& info) {
  StateReader in(path);
  uint64_t file_bytes = in.left();
  Header h = read_header(in, info);
  check_length(in, h, file_bytes);
  HostState s;
  read_arrays(in, h, file_bytes, s);
  if (restartable_state_version(h.version)) {
    uint64_t computed = in.hash(), stored = 0;
    in.value(stored);
    if (stored != computed)
      in.fail("checksum mismatch (stored " + hex16(stored) + ", computed " + hex16(computed) +
              "): the file was changed or damaged after it was written");
  }
  if (std::string problem = state_problem(s, info.step, info.time); !problem.empty())
    in.fail("inconsistent state: " + problem);
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
