// The CPU twin's kick_drift and gather_kick's kick (shaders/kernels/integrate.h) in SIMD lanes
// (Highway, chosen at run time as for the contact lanes): a run of particles at a time, with the
// arithmetic of shaders/kernels/kick.h, the text the GLSL and scalar kernels compile, so the
// bytes are theirs (tests/engine/test_kick_lanes.cpp compares every SIMD target with the scalar
// twin). The scalar kernel cost ~7 ns per particle whether the bed fitted in the caches or not:
// its own instructions, not memory.
#pragma once
#include <cstdint>

namespace repose::gpu {

struct Kernels;

// k_kick_drift(i) for every slot i in [begin, end).
void kick_drift_lanes(Kernels& k, uint64_t begin, uint64_t end);
// k_gather_kick(i) for every slot i in [begin, end): the sums scalar, the kick in lanes.
void gather_kick_lanes(Kernels& k, uint64_t begin, uint64_t end);

}  // namespace repose::gpu
