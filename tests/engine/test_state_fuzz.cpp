// The checkpoint fuzz test: thousands of seeded mutations of small real checkpoints (byte flips,
// field values, truncations, appended bytes), each loaded as `repose run --restart` loads it
// (read_restart_state). Every changed file must be refused with InputError: no crash, no hang,
// no silent acceptance. Mutants whose checksum is recomputed ("forged": a file written wrong, or
// edited with intent) must be refused too when they break an index, a count, a control word, a
// constant of the case or a finite number; those left (physically possible values) must restore
// and step without harm.
#include <catch2/catch.hpp>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <unistd.h>

#include "case/case_loader.h"
#include "engine_test_support.h"
#include "io/restart_state.h"
#include "tests/cli_support.h"
#include "util/input_error.h"

using namespace repose;
using namespace repose::test;
namespace fs = std::filesystem;

namespace {

// In memory where /dev/shm exists: rewriting a file thousands of times on a disk mounted with
// `discard` costs milliseconds each.
std::string scratch(const std::string& name) {
  std::error_code ec;
  fs::path dir = fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm") : fs::temp_directory_path();
  return (dir / ("repose_fuzz_" + std::to_string(::getpid()) + "_" + name)).string();
}

void spill(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(bytes.size()));
}

// A field of the file: bytes [offset, offset + count * width), in 4-byte words (docs/state-format.md).
struct Region {
  const char* name;
  size_t offset, bytes;
};

// The regions of a version 5 file, in order; their sizes must add up to the file's.
std::vector<Region> regions_of(const HostState& s, size_t file_bytes) {
  size_t n = s.pos.size(), c = s.partner.size(), b = s.bodies.size(), r = s.rolling_spring.size();
  std::vector<std::pair<const char*, size_t>> sizes = {
      {"header counts", 16}, {"step and time", 16}, {"case hash", 16}, {"pos", 16 * n}, {"vel", 16 * n},
      {"omega", 16 * n}, {"force", 16 * n}, {"torque", 16 * n}, {"row_start", 4 * (n + 1)}, {"partner", 4 * c},
      {"history", 16 * c}, {"bodies", sizeof(gpu::Body) * b}, {"rolling_spring", 16 * r}, {"control", 32},
      {"pos_at_build", 16 * n}, {"owner", 4 * c}, {"trans_start", 4 * (n + 1)}, {"trans_list", 4 * s.trans_list.size()}};
  std::vector<Region> regions;
  size_t at = 8;
  for (auto [name, bytes] : sizes) {
    if (bytes) regions.push_back({name, at, bytes});
    at += bytes;
  }
  REQUIRE(at + 8 == file_bytes);  // and the checksum
  return regions;
}

// The checksum a writer would give these bytes (of all but the last 8).
std::string forge(std::string bytes) {
  uint64_t sum = state_checksum(kStateVersion, bytes.data(), bytes.size() - 8);
  std::memcpy(&bytes[bytes.size() - 8], &sum, 8);
  return bytes;
}

struct Base {
  std::string name;
  CaseSpec spec;
  Model model;
  std::string hash;
  HostState state;
  std::string bytes;
  std::vector<Region> regions;
};

Base make_base(const std::string& name, const CaseSpec& spec, uint64_t steps) {
  auto sim = simulate(spec, "cpu", 1, {}, 40);
  sim->advance(steps);
  Base b{name, spec, build_model(spec), case_hash(spec), sim->state(), "", {}};
  std::string path = scratch(name + ".state");
  write_state_file(path, sim->state(), sim->step(), sim->time(), b.hash);
  b.bytes = slurp(path);
  b.regions = regions_of(b.state, b.bytes.size());
  fs::remove(path);
  return b;
}

enum class Verdict { Refused, Accepted };

// Loads `bytes` as `repose run --restart` does; anything but InputError is a failure, and so is
// a load that takes long (a count that went unchecked).
Verdict load(const Base& base, const std::string& bytes, RestartPoint* accepted = nullptr,
             std::string* message = nullptr) {
  std::string path = scratch("mutant.state");
  spill(path, bytes);
  auto t0 = std::chrono::steady_clock::now();
  Verdict verdict = Verdict::Accepted;
  try {
    RestartPoint p = read_restart_state(path, base.model, base.hash);
    if (accepted) *accepted = std::move(p);
  } catch (const InputError& e) {
    std::string what = e.what();
    CHECK(what.rfind(path + ": ", 0) == 0);       // names the file
    CHECK(what.find('\n') == std::string::npos);  // in one line
    if (message) *message = what.substr(path.size() + 2);
    verdict = Verdict::Refused;
  }
  CHECK(std::chrono::steady_clock::now() - t0 < std::chrono::seconds(2));
  return verdict;
}

// Values that break indices, counts and floats: all ones, the signed maximum, just past each
// count, NaN, infinities, huge and negative numbers, zero.
std::vector<uint32_t> hostile_words(const Base& b) {
  uint32_t n = uint32_t(b.state.pos.size()), c = uint32_t(b.state.partner.size());
  auto bits = [](float f) { uint32_t u; std::memcpy(&u, &f, 4); return u; };
  return {0u, 1u, 0xFFFFFFFFu, 0x7FFFFFFFu, 0xFFFFFFF0u, 0x80000000u, n, n + 1, c, c + 1, 99999u,
          0x7FC00000u, 0x7F800000u, 0xFF800000u, bits(1e30f), bits(-1.0f), bits(1e-30f), bits(0.5f)};
}

struct Tally {
  int raw = 0, forged = 0, forged_refused = 0, forged_stepped = 0;
};

// One seeded mutant of `b`: a flipped byte, a hostile word in some field (raw or forged), a
// truncation, or appended bytes.
void mutate_once(const Base& b, std::mt19937_64& rng, Tally& t) {
  std::string m = b.bytes;
  auto pick = [&](size_t n) { return size_t(std::uniform_int_distribution<size_t>(0, n - 1)(rng)); };
  int kind = int(pick(5));
  bool forged = false;
  if (kind == 0) {
    m[pick(m.size())] ^= char(1 + pick(255));
  } else if (kind == 1 || kind == 2) {
    const Region& r = b.regions[pick(b.regions.size())];
    auto words = hostile_words(b);
    uint32_t w = words[pick(words.size())];
    std::memcpy(&m[r.offset + 4 * pick(r.bytes / 4)], &w, 4);
    forged = kind == 2;
    if (forged) m = forge(m);
  } else if (kind == 3) {
    m.resize(pick(m.size()));
  } else {
    size_t extra = 1 + pick(64);
    for (size_t k = 0; k < extra; ++k) m.push_back(char(pick(256)));
  }
  if (m == b.bytes) return;  // the hostile value was already there
  INFO(b.name << ": mutation kind " << kind);
  if (!forged) {
    ++t.raw;
    CHECK(load(b, m) == Verdict::Refused);
    return;
  }
  ++t.forged;
  RestartPoint p;
  if (load(b, m, &p) == Verdict::Refused) {
    ++t.forged_refused;
    return;
  }
  // A state with possible values: it must restore and step (a NaN later is physics, not a crash).
  auto sim = simulate(b.spec, "cpu", 1, {}, 8);
  sim->restore(p.state, p.info.step);
  sim->advance(8);
  ++t.forged_stepped;
}

}  // namespace

TEST_CASE("checkpoint fuzz: every changed file is refused, forged ones are refused or harmless", "[engine][io][restart]") {
  CaseSpec cloud = seeded_cloud(40, 5, 2.3, 0.2);  // spheres, a floor and a side wall
  cloud.identity = "cloud";
  CaseSpec clumps = epsd_clump_pairs();  // bodies and EPSD rolling springs
  clumps.identity = "clumps";
  std::vector<Base> bases = {make_base("cloud", cloud, 120), make_base("clumps", clumps, 150)};
  for (const Base& b : bases) REQUIRE(load(b, b.bytes) == Verdict::Accepted);  // the real ones load
  std::mt19937_64 rng(20261126);
  Tally t;
  auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < 5000; ++k) mutate_once(bases[size_t(k % 2)], rng, t);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  WARN(t.raw << " changed files refused; " << t.forged << " forged (checksum recomputed): " << t.forged_refused
              << " refused, " << t.forged_stepped << " with possible values restored and stepped; " << seconds << " s");
  CHECK(t.raw > 2500);
  CHECK(t.forged > 500);
  fs::remove(scratch("mutant.state"));
}

TEST_CASE("a version 5 checkpoint (FNV-1a checksum) still restarts; version 6 ends with XXH3-64", "[engine][io][restart]") {
  CaseSpec spec = seeded_cloud(40, 5, 2.3, 0.2);
  spec.identity = "cloud";
  Base b = make_base("versions", spec, 120);
  REQUIRE(b.bytes.compare(0, 8, std::string(kStateMagic, 8)) == 0);
  uint64_t stored = 0;
  std::memcpy(&stored, &b.bytes[b.bytes.size() - 8], 8);
  const size_t body = b.bytes.size() - 8;
  CHECK(stored == state_checksum(6, b.bytes.data(), body));
  CHECK(stored != state_checksum(5, b.bytes.data(), body));  // the two kinds differ
  // The same bytes as version 5 wrote them: its magic, FNV-1a over everything before the sum.
  std::string v5 = std::string(kStateMagicV5, 8) + b.bytes.substr(8, body - 8);
  uint64_t fnv = state_checksum(5, v5.data(), v5.size());
  v5.append(reinterpret_cast<const char*>(&fnv), 8);
  RestartPoint p;
  REQUIRE(load(b, v5, &p) == Verdict::Accepted);
  CHECK(p.info.version == 5);
  std::string which;
  CHECK(same_state(p.state, b.state, &which));
  INFO(which);
  // A version 5 file with version 6's checksum, and the reverse, are damaged files.
  std::string message;
  std::string v5_with_xxh3 = v5;
  std::memcpy(&v5_with_xxh3[body], &stored, 8);
  CHECK(load(b, v5_with_xxh3, nullptr, &message) == Verdict::Refused);
  CHECK(message.find("checksum mismatch") != std::string::npos);
  std::string v6_with_fnv = b.bytes;
  uint64_t fnv6 = state_checksum(5, b.bytes.data(), body);
  std::memcpy(&v6_with_fnv[body], &fnv6, 8);
  CHECK(load(b, v6_with_fnv, nullptr, &message) == Verdict::Refused);
  CHECK(message.find("checksum mismatch") != std::string::npos);
  fs::remove(scratch("mutant.state"));
}

TEST_CASE("the damaged checkpoints of issue 23 are refused by what is wrong", "[engine][io][restart]") {
  CaseSpec spec = seeded_cloud(40, 5, 2.3, 0.2);
  spec.identity = "cloud";
  Base b = make_base("issue23", spec, 120);
  auto region = [&](const std::string& name) {
    for (const Region& r : b.regions)
      if (name == r.name) return r.offset;
    FAIL("no region " << name);
    return size_t(0);
  };
  auto set_word = [&](std::string bytes, size_t at, uint32_t v) {
    std::memcpy(&bytes[at], &v, 4);
    return bytes;
  };
  auto set_float = [&](std::string bytes, size_t at, float v) {
    std::memcpy(&bytes[at], &v, 4);
    return bytes;
  };
  uint32_t c = uint32_t(b.state.partner.size());
  std::string appended = b.bytes + std::string(64, '\0'), flipped = b.bytes;
  flipped[flipped.size() / 2] ^= 0x10;
  // Each also forged (the checksum recomputed): the validation alone must refuse it.
  std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      {"partner[0] = 0xFFFFFFFF", set_word(b.bytes, region("partner"), 0xFFFFFFFFu), "partner[0] = 4294967295"},
      {"owner[0] = 99999", set_word(b.bytes, region("owner"), 99999u), "owner[0] = 99999"},
      {"trans_list[0] = 0xFFFFFFF0", set_word(b.bytes, region("trans_list"), 0xFFFFFFF0u), "trans_list[0]"},
      {"contact count word = 0x7FFFFFFF", set_word(b.bytes, region("control") + 12, 0x7FFFFFFFu), "control word 3"},
      {"header C + 1", set_word(b.bytes, region("header counts") + 4, c + 1), "truncated, or bytes appended"},
      {"overflow word = 1", set_word(b.bytes, region("control") + 8, 1u), "overflow flag"},
      {"row_start out of range", set_word(b.bytes, region("row_start") + 4, 99999u), "row_start descends"},
      {"NaN position", set_float(b.bytes, region("pos"), std::nanf("")), "pos[0] holds a number that is not finite"},
      {"1e30 position", set_float(b.bytes, region("pos"), 1e30f), "so far out that a float cannot resolve"},
      {"radius -1", set_float(b.bytes, region("pos") + 12, -1.0f), "radius -1 m is not positive"},
      {"1/mass = 0", set_float(b.bytes, region("vel") + 12, 0.0f), "particle 0's 1/mass is 0 in the state"},
  };
  for (const auto& [what, bytes, expected] : cases)
    for (bool forged : {false, true}) {
      std::string message;
      INFO(what << (forged ? " (forged)" : ""));
      REQUIRE(load(b, forged ? forge(bytes) : bytes, nullptr, &message) == Verdict::Refused);
      INFO(message);
      // A changed count shows in the length before the checksum is read.
      bool by_checksum = !forged && what != "header C + 1";
      CHECK(message.find(by_checksum ? "checksum mismatch" : expected) != std::string::npos);
    }
  std::string message;
  CHECK(load(b, appended, nullptr, &message) == Verdict::Refused);
  CHECK(message.find("bytes appended") != std::string::npos);
  CHECK(load(b, flipped, nullptr, &message) == Verdict::Refused);
  CHECK(message.find("checksum mismatch") != std::string::npos);
  // Another case with as many particles: named by both hashes.
  CaseSpec other = seeded_cloud(40, 6, 2.3, 0.2);
  other.identity = "another cloud";
  Base o = make_base("other", other, 120);
  CHECK(load(b, o.bytes, nullptr, &message) == Verdict::Refused);
  CHECK(message.find("written by a run of case " + o.hash + ", not of this case (" + b.hash) != std::string::npos);
  fs::remove(scratch("mutant.state"));
}

TEST_CASE("run --restart of a damaged checkpoint: exit 2, one line, no folder", "[engine][cli][restart]") {
  fs::path dir = scratch("cli");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string run = std::string("run ") + REPOSE_SOURCE_DIR + "/cases/settle_box.toml --backend cpu --quiet --set fill.0.count=60 ";
  REQUIRE(run_repose(run + "--steps 40 --out " + (dir / "a").string() + " --state-out " + (dir / "k.state").string()).status == 0);
  std::string good = slurp((dir / "k.state").string()), flipped = good, cut = good.substr(0, good.size() - 5);
  flipped[good.size() / 3] ^= 0x01;
  for (const auto& [name, bytes] : {std::pair{"flipped", flipped}, {"cut", cut}}) {
    std::string path = (dir / (std::string(name) + ".state")).string();
    spill(path, bytes);
    auto r = run_repose(run + "--steps 10 --restart " + path + " --out " + (dir / "b").string());
    INFO(name << ": " << r.output);
    CHECK(r.status == 2);
    CHECK(r.output.find(path + ": ") != std::string::npos);
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
    CHECK_FALSE(fs::exists(dir / "b"));
  }
  auto folder = run_repose(run + "--steps 10 --restart " + dir.string() + " --out " + (dir / "b").string());
  CHECK(folder.status == 2);
  CHECK(folder.output.find(dir.string() + ": a folder, not a file") != std::string::npos);
  auto fine = run_repose(run + "--steps 10 --restart " + (dir / "k.state").string() + " --out " + (dir / "b").string());
  CHECK(fine.status == 0);
  fs::remove_all(dir);
}
