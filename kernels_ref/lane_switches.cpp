#include "lane_switches.h"

#include <atomic>

namespace repose::gpu {

namespace {
std::atomic<bool> g_on[4] = {true, true, true, true};
}

void set_lanes(LaneKernels which, bool on) { g_on[int(which)].store(on, std::memory_order_relaxed); }
bool lanes_enabled(LaneKernels which) { return g_on[int(which)].load(std::memory_order_relaxed); }

}  // namespace repose::gpu
