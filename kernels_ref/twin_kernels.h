// The shared kernel bodies (shaders/kernels/*.h) compiled as C++: included inside a struct whose
// members carry the shaders' global names, so the same text is valid GLSL and C++. In GLSL,
// B_name[] is a storage buffer and PC the push constants (kernels/glsl_prelude.glsl); here they
// are the struct's pointers into the CPU twin's buffers and its copy of the push constants, and
// every kernel function is a member (implicitly inline, so the bodies inline into run_kernel's
// loops). Compile with -ffp-contract=off (CMakeLists.txt).
#pragma once
#include "cpu_kernels.h"

namespace repose::gpu {

struct Kernels {
#define REPOSE_KERNEL_BUFFER(binding, Name, name, type, count, need, keep) type* B_##name = nullptr;
  REPOSE_BUFFERS(REPOSE_KERNEL_BUFFER)
#undef REPOSE_KERNEL_BUFFER
  SimPush PC{};
  int32_t uniform_material = -1;  // Buffers::uniform_material
  float* walk_rows = nullptr;  // Buffers::walk_rows

  Kernels() = default;
#define REPOSE_KERNEL_BUFFER_FROM(binding, Name, name, type, count, need, keep) B_##name(b.name),
  explicit Kernels(const Buffers& b)
      : REPOSE_BUFFERS(REPOSE_KERNEL_BUFFER_FROM) PC(b.push), uniform_material(b.uniform_material),
        walk_rows(b.walk_rows) {}
#undef REPOSE_KERNEL_BUFFER_FROM

// The GLSL prelude's wall_kind_possible() lets lavapipe compile out the code of wall kinds a run
  // lacks; the twin branches on the kind alone (the extra test cost it ~20 % of contact_forces).
  static constexpr bool wall_kind_possible(uint) { return true; }

#include "kernels/all.h"

  // walk_neighbours' row of cells and large bucket (the GLSL prelude's are walk_cells and walk_large;
  // contact_count's lanes walk them in SIMD lanes instead, walk_lanes.cpp).
  uint walk_row(uint i, vec4 pi, int x0, int x1, ivec3 c, uint begin, uint end, uint lowest, bool i_fixed, bool fill,
                uint base, uint k, uint old_begin, uint old_end) {
    return walk_cells(i, pi, x0, x1, c, begin, end, lowest, i_fixed, fill, base, k, old_begin, old_end);
  }
  uint walk_large_bucket(uint i, vec4 pi, uint lowest, uint begin, uint end, bool fill, uint base, uint k,
                         uint old_begin, uint old_end) {
    return walk_large(i, pi, lowest, begin, end, fill, base, k, old_begin, old_end);
  }
};

}  // namespace repose::gpu
