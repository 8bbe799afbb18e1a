// The dispatch programs of a simulation: the first force evaluation and one time step.
// Written once for both backends.
#pragma once
#include <vector>

#include "engine/backend.h"
#include "engine/model.h"

namespace repose {

enum class ContactKernel { PerContact, PerRow };

struct KernelVariant {
  uint32_t workgroup = gpu::kDefaultWorkgroup;
  ContactKernel contact = ContactKernel::PerContact;
  uint32_t rebuild_interval = 0;  // forced rebuild every N steps (0: skin check only)
  // Lean contact entries (32 B instead of 48 B of forces per contact; torques rebuilt in the
  // gather, shaders/kernels/contacts.h). Same bytes as the full entries.
  bool lean = false;
  // Store the particles in cell order (host/engine/particle_order.h) before the first batch and
  // again after this many list rebuilds; 0: in the case's order. Same bytes either way.
  uint32_t reorder = kDefaultReorder;
  static constexpr uint32_t kDefaultReorder = 20;
  // Unless named (reorder=N: exactly every N rebuilds), a reorder also waits until it would take
  // at most a tenth of the run's wall time (host/engine/reorder_schedule.h).
  bool reorder_capped = true;
  std::string name() const;
  // "rows,lean,wg=128,rebuild=20,reorder=10" -> variant; throws std::invalid_argument on anything else.
  static KernelVariant parse(const std::string& text);
  // What a run on `backend` ("vulkan" or "cpu") uses when the user names no variant: lean
  // entries on Vulkan (lavapipe runs them faster: less to load per contact), unless the model
  // stores torques per contact (EPSD rolling springs, spinning friction need full entries);
  // the cpu backend's contact lanes write full ones.
  static KernelVariant fastest_for(const std::string& backend, const Model& m);
};

// The buffer layout of model m run with variant v, `batch_steps` wall states per upload and a
// list of `capacity` entries (the simulation's to choose; 0 until it does). Throws
// std::invalid_argument for lean entries with an option that needs full ones
// (gpu::kFlagsNeedFullEntries).
Layout model_layout(const Model& m, const KernelVariant& v, uint32_t batch_steps, uint32_t capacity = 0);

// walls_still: no wall moves during the steps this push serves, so no rebuild is forced for walls
// (Model::still_interval instead of max_interval; results do not depend on when lists are built).
gpu::SimPush base_push(const Model& m, const Layout& l, const KernelVariant& v, bool walls_still = false);

// Workgroups per dispatch row along x: gpu::kMaxGroupsX, or less with the environment variable
// REPOSE_MAX_GROUPS_X (tests lower it to run the split dispatches of large runs on small ones).
// The same on both backends, so their indirect arguments agree to the byte.
uint32_t max_groups_x();

// A scan of this many blocks of gpu::kScanBlock entries or more takes the three block passes
// over the whole device (shaders/scan.comp); a shorter one stays in one workgroup, whose few
// blocks should cost less on a GPU than two more dispatches and barriers (reasoned, not yet
// measured: scripts/gpu-check.sh benches both). lavapipe, which runs a
// workgroup at a time per CPU thread and pays ~50 us to start each, is faster in one workgroup at
// every size (docs/engineering.md, "The scan"); it is the tests' device, not a user's.
inline constexpr uint32_t kScanBlocksFrom = 8;
// kScanBlocksFrom, or less with the environment variable REPOSE_SCAN_BLOCKS_FROM (tests lower it
// to 1 to run the block passes in small cases; a GPU's bench compares the two paths with it).
uint32_t scan_blocks_from();
// Whether a scan of `count` entries takes the block passes.
bool scan_in_blocks(uint32_t count);
// The dispatches of an exclusive scan of `count` entries of `target` (gpu::kScanCells: the T+1
// bucket counts; kScanRows, kScanTransposed: the N rows) in a rebuild: one workgroup, or the
// block passes over the groups that rebuild_args writes for that many entries (none when the
// step does not rebuild).
std::vector<Dispatch> scan_dispatches(uint32_t target, uint32_t count, bool in_blocks);

// Places every sub-sphere from its body (empty without bodies): run once before the first step.
std::vector<Dispatch> body_place_program(const Model& m, const Layout& l, const KernelVariant& v);
// Neighbour list, forces and F(0) without moving anything (kick 0).
std::vector<Dispatch> initial_forces_program(const Model& m, const Layout& l,
                                             const KernelVariant& v, uint32_t wall_slot);
// One step of the model's integrator; walls at row `wall_slot` of the uploaded batch.
std::vector<Dispatch> step_program(const Model& m, const Layout& l, const KernelVariant& v,
                                   uint32_t wall_slot, bool walls_still = false);

}  // namespace repose
