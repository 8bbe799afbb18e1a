// The CPU twin's contact kernel run over several contacts at once in SIMD lanes (Highway, chosen
// at run time for the machine: SSE4, AVX2, AVX-512). Each lane does the IEEE operations of
// process_contact (shaders/kernels/contacts.h, contact_law.h) in the same order, so the bytes are
// those of the scalar twin and of lavapipe; tests/engine/test_contact_lanes.cpp checks that for
// every option the lanes take. A wall contact's geometry is the scalar kernel's, its law runs in
// lanes with other wall contacts; the tail of a range and options the lanes do not cover (rolling
// springs, spinning friction) run the scalar kernel.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace repose::gpu {

struct Kernels;

// Whether the lanes cover a step with these SimPush flags.
bool contact_lanes_cover(uint32_t flags);
// process_contact(B_owner[c], c) for every c in [begin, end), in lanes where they cover it.
void contact_forces_lanes(Kernels& k, uint64_t begin, uint64_t end);
// The law's arithmetic alone over `batches` batches of contacts_lanes_width() contacts (the
// bench's compute ceiling): a few batches of the list's particle pairs copied once into lanes'
// layout, within L1, the law run over them again and again, kSinkFloats per lane stored into
// `sink` (kLawRing batches of them: kLawRing * kSinkFloats * width floats) as the kernel stores its entries.
constexpr size_t kLawRing = 8, kSinkFloats = 16;  // history, force, T_i (lean: n x Ft, overlap), T_j
void contact_law_lanes(Kernels& k, uint64_t batches, float* sink);
size_t contact_lanes_width();
// The SIMD target Highway picked on this machine ("AVX3", "AVX2", ...), for bench reports.
const char* contact_lanes_target();
// The SIMD targets (Highway's bits) this machine can run the lanes on, for tests that compare
// them; pin_contact_lanes_target(t) makes the lanes use t only (0: the best one again).
std::vector<int64_t> contact_lanes_targets();
void pin_contact_lanes_target(int64_t target);

}  // namespace repose::gpu
