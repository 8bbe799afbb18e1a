// Where each particle sits in the device buffers. A particle's global id is its place in the case
// (the order of Model::pos, of the host's state and of every output); its slot is where the
// device stores it. Storing neighbours in nearby slots (cell order) keeps a walk's reads in cache;
// the kernels order every float sum by global id (shaders/repose_shared.h), so the bytes of a run
// do not depend on the slots. Simulation converts between the two at the host/device boundary.
#pragma once
#include <cstdint>
#include <vector>

#include "engine/backend.h"

namespace repose {

struct Model;

struct ParticleOrder {
  std::vector<uint32_t> id_of;    // slot -> global id
  std::vector<uint32_t> slot_of;  // global id -> slot

  static ParticleOrder identity(uint32_t n);
  // The order that stores global id id_of[s] in slot s; throws std::invalid_argument unless
  // id_of is a permutation of 0..n-1.
  static ParticleOrder from_ids(std::vector<uint32_t> id_of);
  bool is_identity() const;
  size_t size() const { return id_of.size(); }
  // The device's id table (binding Ids): id_of, then slot_of.
  std::vector<uint32_t> table() const;
};

// Slots in the order of the grid cells of edge `cell` holding each position (by global id): by
// layer (z), row (y), then along the row (x), ties by global id. A walk's neighbours then sit in
// a few runs of slots that advance together, which the CPU's prefetchers follow (on the settled
// 50k bed, contact_forces 1.6-1.8 ms per step in these rows, 1.7-2.6 in Morton order, 2.1-3.1 in
// the fill's random order; README, speed). With `bodies`, a body moves as one: bodies in the order
// of their centres' cells, each body's sub-spheres in consecutive slots by global id, so the
// per-body gather (body_gather_kick) reads a run of slots, not one scattered row per sub-sphere
// (docs/engineering.md, particle order).
// Keyed and sorted on up to `threads` threads (the same order on any number).
ParticleOrder cell_order(const std::vector<gpu::vec4>& pos, const std::vector<gpu::Body>& bodies, double cell,
                         unsigned threads = 1);
// The same order from positions held in any order, pos[r] being particle id_of_row[r]'s (the
// slots of a state as the device stores it): sorted by cell, then by global id, as above.
ParticleOrder cell_order(const std::vector<gpu::vec4>& pos, const std::vector<uint32_t>& id_of_row,
                         const std::vector<gpu::Body>& bodies, double cell, unsigned threads = 1);

// The host state (rows by global id, contacts as the kernels would list them by global id) moved
// into the slots the device stores them in under `order`, and back: per-particle rows, the contact
// lists' rows with their owners (keeping their order) and the indices in them. A row at a time,
// so a conversion holds one row twice, never a second state (engine/memory_need.cpp); each row in
// blocks on up to `threads` threads (each block writes its own part: the same bytes on any number).
void to_stored(HostState& state, const ParticleOrder& order, unsigned threads = 1);
void to_global(HostState& state, const ParticleOrder& order, unsigned threads = 1);
// A state stored under `from` moved into the slots of `to`: to_global and to_stored in one pass.
void to_other_slots(HostState& state, const ParticleOrder& from, const ParticleOrder& to, unsigned threads = 1);
// For each contact of the stored list, its index in `global`'s list.
std::vector<uint32_t> stored_contact_ids(const HostState& global, const ParticleOrder& order);

// The model's constant rows as the device stores them under `order`, with the id table.
ConstantData stored_constants(const Model& m, const ParticleOrder& order);

}  // namespace repose
