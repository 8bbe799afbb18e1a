// How close the kernels run to the machine's memory bandwidth (a roofline): the bytes each
// kernel must move, and a STREAM-like copy measured in the same run to divide them by.
//
// A kernel's bytes are what it cannot avoid with a perfect cache: every element of every buffer
// it reads, once, and of every buffer it writes, once (a read-modify-write twice). The table in
// kernel_traffic.cpp lists the buffers of each kernel of a sphere step and of a list rebuild
// (shaders/kernels/*.h); clumps' kernels are not in it. Element sizes come from the buffer
// table, so only a kernel that starts or stops using a buffer changes it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "engine/backend.h"

namespace repose {

class ThreadPool;

// What the kernels run over.
struct TrafficCounts {
  double particles = 0;
  double contacts = 0;      // entries in the list (the control word), not its capacity
  double old_contacts = 0;  // the list a rebuild replaces (about the same)
  double buckets = 0;       // hash buckets (table size)
};

// Bytes one dispatch of `kernel` moves at the least for this layout (lean entries, rolling
// springs); 0 for a kernel the table does not hold.
double kernel_min_bytes(const std::string& kernel, const Layout& layout, const TrafficCounts& counts);

// True for the kernels that run only in a step that rebuilds the list.
bool rebuild_kernel(const std::string& kernel);

// A copy between two arrays of `bytes` each, split over `pool`'s threads as the cpu backend splits
// its kernels, kept to be timed again: bandwidth() counts the read and the write (STREAM's
// convention), the best of `passes`.
class CopyMeter {
 public:
  CopyMeter(size_t bytes, ThreadPool& pool);
  double bandwidth(int passes = 5);

 private:
  std::vector<double> from_, to_;
  ThreadPool& pool_;
};

}  // namespace repose
