// How much memory this process uses and how much more it may take: the figures a run checks
// before it starts (engine/memory_need.h) and `repose bench` reports.
#pragma once
#include <cstddef>
#include <string>

namespace repose {

// Bytes this process may still allocate: the least of the system's MemAvailable
// (/proc/meminfo), what its memory cgroup (v2 memory.max, v1 memory.limit_in_bytes) has left
// over its current use, and what RLIMIT_AS (ulimit -v) leaves over its virtual size.
struct AvailableMemory {
  size_t bytes = 0;
  std::string limited_by;  // "MemAvailable", "cgroup memory.max", "ulimit -v" ...
};
AvailableMemory available_memory();

// The largest resident set of this process so far (getrusage ru_maxrss), bytes.
size_t peak_resident_bytes();
// Its resident set now (/proc/self/statm), bytes; 0 when unreadable.
size_t resident_bytes();

// "1.23 GiB", "456 MiB", "789 KiB".
std::string format_bytes(double bytes);

}  // namespace repose
