// The CPU twin's per-sub-sphere body kernels (shaders/kernels/bodies.h) in SIMD lanes (Highway,
// chosen at run time as for the contact lanes): body_place a run of sub-spheres at a time,
// body_gather_kick a body per lane, each lane summing its body's sub-spheres in their order. The
// arithmetic is shaders/kernels/rigid_body.h, the text the GLSL and scalar kernels compile, so
// the bytes are theirs (tests/engine/test_body_lanes.cpp compares every SIMD target with the
// scalar twin). A heap of clumps spends most of a step here: the cotton-stalk study's 720-sphere
// stalks at rest, 326,880 sub-spheres with 2,429 touching pairs (docs/engineering.md).
#pragma once
#include <cstdint>

namespace repose::gpu {

struct Kernels;

// k_body_place(i) for every slot i in [begin, end).
void body_place_lanes(Kernels& k, uint64_t begin, uint64_t end);
// k_body_gather_kick(b) for every body b in [begin, end).
void body_gather_kick_lanes(Kernels& k, uint64_t begin, uint64_t end);

}  // namespace repose::gpu
