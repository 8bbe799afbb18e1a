#include "util/memory_info.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace repose {

namespace {

// A "KEY: N kB" line of a /proc file, in bytes; 0 when absent.
size_t proc_kib_field(const char* path, const std::string& key) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
    if (line.compare(0, key.size() + 1, key + ":") == 0) return size_t(std::stoull(line.substr(key.size() + 1))) * 1024;
  return 0;
}

// The first number in a file, or 0 when it is missing or says "max" (no limit).
size_t number_in(const std::string& path) {
  std::ifstream in(path);
  unsigned long long v = 0;
  return in >> v ? size_t(v) : 0;
}

// What this process's memory cgroup leaves: limit minus use, or 0 when it sets no limit.
// /proc/self/cgroup names the group: "0::PATH" (v2) or "N:memory:PATH" (v1).
size_t cgroup_room(std::string& which) {
  std::ifstream in("/proc/self/cgroup");
  std::string line;
  while (std::getline(in, line)) {
    bool v2 = line.rfind("0::", 0) == 0;
    size_t colon = line.find(':');
    bool v1 = colon != std::string::npos && line.compare(colon, 8, ":memory:") == 0;
    if (!v2 && !v1) continue;
    std::string group = line.substr(line.rfind(':') + 1);
    // Inside a container the group's own folder is often mounted as the root.
    for (const std::string& dir : {group, std::string()}) {
      std::string base = (v2 ? "/sys/fs/cgroup" : "/sys/fs/cgroup/memory") + dir;
      size_t limit = number_in(base + (v2 ? "/memory.max" : "/memory.limit_in_bytes"));
      if (limit == 0 || limit >= (size_t(1) << 60)) continue;  // absent, or "no limit"
      size_t used = number_in(base + (v2 ? "/memory.current" : "/memory.usage_in_bytes"));
      which = v2 ? "cgroup memory.max" : "cgroup memory.limit_in_bytes";
      return limit > used ? limit - used : 1;
    }
  }
  return 0;
}

}  // namespace

AvailableMemory available_memory() {
  AvailableMemory a{proc_kib_field("/proc/meminfo", "MemAvailable"), "MemAvailable"};
  auto consider = [&](size_t room, const std::string& why) {
    if (room && (a.bytes == 0 || room < a.bytes)) a = {room, why};
  };
  std::string which;
  size_t cgroup = cgroup_room(which);
  consider(cgroup, which);
  rlimit as{};
  if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY) {
    size_t virt = proc_kib_field("/proc/self/status", "VmSize");
    consider(as.rlim_cur > virt ? size_t(as.rlim_cur - virt) : 1, "ulimit -v");
  }
  return a;
}

size_t peak_resident_bytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return size_t(u.ru_maxrss) * 1024;  // Linux reports KiB
}

size_t resident_bytes() {
  std::ifstream in("/proc/self/statm");
  size_t pages = 0, resident = 0;
  if (!(in >> pages >> resident)) return 0;
  return resident * size_t(sysconf(_SC_PAGESIZE));
}

std::string format_bytes(double bytes) {
  char text[32];
  if (bytes >= 1024.0 * 1024 * 1024) std::snprintf(text, sizeof text, "%.2f GiB", bytes / (1024.0 * 1024 * 1024));
  else if (bytes >= 1024.0 * 1024) std::snprintf(text, sizeof text, "%.0f MiB", bytes / (1024.0 * 1024));
  else std::snprintf(text, sizeof text, "%.0f KiB", bytes / 1024.0);
  return text;
}

}  // namespace repose
