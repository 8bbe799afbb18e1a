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
  Particles, ParticlesPlusOne, ParticlesTwice, Contacts, ContactsTwice, Transposed, Buckets, BucketsPlusOne, Pairs, WallRows,
  WallSums, Bodies, Control, CandidateSlots, Parts, ScanBlocks, WallGrid
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
  constexpr bool alias() const { return need == BufferNeed::Alias; }
};

// The rows in table order (kRowPos, kRowVel, ...).
enum BufferRow : uint32_t {
#define REPOSE_ROW(binding, Name, name, type, count, need, keep) kRow##Name,
  REPOSE_BUFFERS(REPOSE_ROW)
#undef REPOSE_ROW
  kBufferRows
};

inline constexpr std::array<BufferSpec, kBufferRows> kBufferTable = {{
#define REPOSE_SPEC(binding, Name, name, type, count, need, keep) \
  {binding, #name, sizeof(gpu::type), BufferCount::count, BufferNeed::need, BufferKeep::keep},
    REPOSE_BUFFERS(REPOSE_SPEC)
#undef REPOSE_SPEC
}};

// The buffers come first, as descriptors 0, 1, 2, ... (so kBufferTable[binding] is a buffer's own
// row); the aliases follow, each naming one of them.
constexpr bool buffer_bindings_in_order() {
  uint32_t next = 0;
  for (const BufferSpec& b : kBufferTable) {
    if (b.alias() ? b.binding >= next : (b.binding != next++ || next > gpu::kBindingCount)) return false;
  }
  return next == gpu::kBindingCount;
}
static_assert(buffer_bindings_in_order(), "REPOSE_BUFFERS: buffers numbered 0, 1, 2, ..., then aliases naming one");

// Elements of buffer b for the layout; 0 when the layout does not need it.
size_t buffer_elements(const BufferSpec& b, const Layout& l);
// Bytes of a binding's memory: the largest of the rows that view it (a buffer and its aliases).
size_t binding_bytes(uint32_t binding, const Layout& l);
// Elements of a kept buffer that hold state (what download_state copies): all of them, or for
// the contact list the entries in use, from the control words and trans_start of `s` (visited
// before, in binding order).
size_t used_elements(const BufferSpec& b, const Layout& l, const HostState& s);
// Device bytes per entry of the contact list (all buffers counted by contacts).
size_t bytes_per_contact(const Layout& l);

// f(spec, vector) for every State and File row, in binding order.
template <class State, class F>
void for_each_kept(State& s, F&& f) {
#define REPOSE_VISIT(binding, Name, name, type, count, need, keep) REPOSE_VISIT_##keep(Name, name)
#define REPOSE_VISIT_State(Name, name) f(kBufferTable[kRow##Name], s.name);
#define REPOSE_VISIT_File(Name, name) f(kBufferTable[kRow##Name], s.name);
#define REPOSE_VISIT_Constant(Name, name)
#define REPOSE_VISIT_Scratch(Name, name)
#define REPOSE_VISIT_Walls(Name, name)
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
#define REPOSE_VISIT(binding, Name, name, type, count, need, keep) REPOSE_VISIT_##keep(Name, name)
#define REPOSE_VISIT_Constant(Name, name) f(kBufferTable[kRow##Name], c.name);
#define REPOSE_VISIT_State(Name, name)
#define REPOSE_VISIT_File(Name, name)
#define REPOSE_VISIT_Scratch(Name, name)
#define REPOSE_VISIT_Walls(Name, name)
  REPOSE_BUFFERS(REPOSE_VISIT)
#undef REPOSE_VISIT_State
#undef REPOSE_VISIT_File
#undef REPOSE_VISIT_Constant
#undef REPOSE_VISIT_Scratch
#undef REPOSE_VISIT_Walls
#undef REPOSE_VISIT
}

}  // namespace repose
