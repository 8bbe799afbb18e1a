// The full state of a run, as bytes in a stable, documented order (docs/state-format.md), so that
// two runs, two thread counts or two backends can be compared with `cmp`, and a run can continue
// from it (`repose run --restart`) to the same bytes as a run that never stopped.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/backend.h"

namespace repose {

// Version 6 ends with an XXH3-64 checksum instead of FNV-1a 64: the same bytes before it, hashed
// at memory speed (FNV-1a's chain of a multiply per byte was ~80 % of writing a file). Version 5
// adds the case's hash and a checksum of every byte (a changed or damaged file is refused).
// Version 4 added what a restart needs beyond the physics (the neighbour-list bookkeeping: control
// counters, positions at the last rebuild, the contacts' owners and transposed index). Version 3
// added the rolling springs. Versions 5 and 6 restart; versions 2 to 4 still read, but cannot be
// restarted.
constexpr char kStateMagic[8] = {'R', 'E', 'P', 'O', 'S', 'E', 'S', '6'};
constexpr char kStateMagicV5[8] = {'R', 'E', 'P', 'O', 'S', 'E', 'S', '5'};
constexpr char kStateMagicV4[8] = {'R', 'E', 'P', 'O', 'S', 'E', 'S', '4'};
constexpr char kStateMagicV3[8] = {'R', 'E', 'P', 'O', 'S', 'E', 'S', '3'};
constexpr char kStateMagicV2[8] = {'R', 'E', 'P', 'O', 'S', 'E', 'S', '2'};
constexpr int kStateVersion = 6;
// The first version with a checksum and a case hash: the first a run can restart from.
constexpr int kRestartableStateVersion = 5;
// Versions from kRestartableStateVersion on hold a case hash after the header and end with a checksum.
constexpr bool restartable_state_version(int version) { return version >= kRestartableStateVersion; }
// Control words 0 .. kRestartControlWords-1 (need-rebuild flag to old-contact count) are stored;
// the dispatch sizes after them depend on the kernel variant and are recomputed on restart.
constexpr uint32_t kRestartControlWords = 8;
// The case hash field: 16 hex digits (io/provenance.h), zero bytes when written without one.
constexpr size_t kStateCaseHashBytes = 16;

struct StateFileInfo {
  uint64_t step = 0;
  double time = 0;
  int version = 0;
  std::string case_hash;  // of the case that wrote it (version 5 on), "" when not recorded
  bool restartable() const { return restartable_state_version(version); }
};

// The checksum that ends a file of a restartable version (docs/state-format.md) over `bytes`:
// FNV-1a 64 in version 5, XXH3-64 (seed 0) from version 6.
uint64_t state_checksum(int version, const void* data, size_t bytes);

// `case_hash`: the hash of the case it belongs to (case_hash(spec)), checked on restart.
void write_state_file(const std::string& path, const HostState& state, uint64_t step, double time,
                      const std::string& case_hash = "");
// Reads a file written by write_state_file: its length, checksum and every index, count and
// number (io/state_validation.h). Throws InputError naming the file and what is wrong.
HostState read_state_file(const std::string& path, uint64_t* step = nullptr, double* time = nullptr);
HostState read_state_file(const std::string& path, StateFileInfo& info);

}  // namespace repose
