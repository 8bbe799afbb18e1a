// The device buffers of the table in shaders/repose_shared.h, seen from the host: how many
// elements each holds for a layout, which ones the host keeps, and typed visits of those, so
// both backends and the state file follow the table instead of listing buffers themselves.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>

#include "engine/backend.h"

namespace repose {

enum class BufferCount {
  Particles, ParticlesPlusOne, Contacts, ContactsTwice, Transposed, Buckets, BucketsPlusOne, Pairs, WallRows,
  Walls, Bodies, Control
};
enum class BufferNeed { Always, FullEntries, Bodies, RollingSprings, Alias };
enum class BufferKeep { Scratch, State, File, Constant, Walls };

struct BufferSpec {
  uint32_t binding;
  const char* name;
  size_t element_bytes;
  BufferCount count;
  BufferNeed need;
  BufferKeep keep;
  int alias;  // the binding whose memory an Alias row shares, else -1
};

// The rows, indexed by binding.
inline constexpr std::array<BufferSpec, gpu::kBindingCount> kBufferTable = {{
#define REPOSE_SPEC(binding, Name, name, type, count, need, keep, alias) \
  {binding, #name, sizeof(gpu::type), BufferCount::count, BufferNeed::need, BufferKeep::keep, alias},
    REPOSE_BUFFERS(REPOSE_SPEC)
#undef REPOSE_SPEC
}};

constexpr bool buffer_rows_in_binding_order() {
  for (uint32_t b = 0; b < gpu::kBindingCount; ++b)
    if (kBufferTable[b].binding != b) return false;
  return true;
}
static_assert(buffer_rows_in_binding_order(), "REPOSE_BUFFERS rows must be numbered 0, 1, 2, ...");

// Elements of buffer b for the layout; 0 when the layout does not need it (an alias counts its
// own elements; its memory is its target's).
size_t buffer_elements(const BufferSpec& b, const Layout& l);
// Elements of a kept buffer that hold state (what download_state copies): all of them, or for
// the contact list the entries in use, from the control words and trans_start of `s` (visited
// before, in binding order).
size_t used_elements(const BufferSpec& b, const Layout& l, const HostState& s);
// Device bytes per entry of the contact list (all buffers counted by contacts).
size_t bytes_per_contact(const Layout& l);

// f(spec, vector) for every State and File row, in binding order.
template <class State, class F>
void for_each_kept(State& s, F&& f) {
#define REPOSE_VISIT(binding, Name, name, type, count, need, keep, alias) REPOSE_VISIT_##keep(binding, name)
#define REPOSE_VISIT_State(binding, name) f(kBufferTable[binding], s.name);
#define REPOSE_VISIT_File(binding, name) f(kBufferTable[binding], s.name);
#define REPOSE_VISIT_Constant(binding, name)
#define REPOSE_VISIT_Scratch(binding, name)
#define REPOSE_VISIT_Walls(binding, name)
  REPOSE_BUFFERS(REPOSE_VISIT)
#undef REPOSE_VISIT_State
#undef REPOSE_VISIT_File
#undef REPOSE_VISIT_Constant
#undef REPOSE_VISIT_Scratch
#undef REPOSE_VISIT_Walls
#undef REPOSE_VISIT
}

// f(spec, vector) for every Constant row.
template <class F>
void for_each_constant(const ConstantData& c, F&& f) {
#define REPOSE_VISIT(binding, Name, name, type, count, need, keep, alias) REPOSE_VISIT_##keep(binding, name)
#define REPOSE_VISIT_Constant(binding, name) f(kBufferTable[binding], c.name);
#define REPOSE_VISIT_State(binding, name)
#define REPOSE_VISIT_File(binding, name)
#define REPOSE_VISIT_Scratch(binding, name)
#define REPOSE_VISIT_Walls(binding, name)
  REPOSE_BUFFERS(REPOSE_VISIT)
#undef REPOSE_VISIT_State
#undef REPOSE_VISIT_File
#undef REPOSE_VISIT_Constant
#undef REPOSE_VISIT_Scratch
#undef REPOSE_VISIT_Walls
#undef REPOSE_VISIT
}

}  // namespace repose
