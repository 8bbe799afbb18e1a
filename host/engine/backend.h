// What the simulation driver needs from a compute backend. Two implement it: the Vulkan one
// (shaders on any Vulkan device, lavapipe included) and the CPU twin (the same kernels in C++).
// Both execute the same dispatch programs (step_program.h), so they produce the same bytes.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "kernel_ids.h"
#include "repose_shared.h"

namespace repose {

// Buffer sizes of one simulation.
struct Layout {
  uint32_t n_particles = 0;
  uint32_t n_walls = 0;
  uint32_t n_materials = 0;
  uint32_t table_size = 0;
  uint32_t capacity = 0;     // contact list entries
  uint32_t n_bodies = 0;     // rigid bodies; 0: every particle is a free sphere
  uint32_t batch_steps = 1;  // wall states per upload
  bool lean_contacts = false;  // no torque_j buffer (KernelVariant::lean)
  bool rolling_springs = false;  // kFlagRollingSpring: a rolling spring per contact (and the old list's)
};

// Inputs that stay constant during a run, uploaded with every allocation.
struct ConstantData {
  std::vector<uint32_t> material;
  std::vector<gpu::PairParams> pairs;
  std::vector<gpu::SubSphere> subs;  // one per particle with bodies, else empty
};

// Device bytes per contact-list entry: partner, owner and transposed index, history, and the
// force entry (full: force, torque_i, torque_j; lean: two vec4). The rebuild-only old_partner
// and old_history share the memory of trans_list and contact_force, which every rebuild
// rewrites after it has read them (shaders/repose_shared.h).
inline size_t bytes_per_contact(const Layout& l) {
  return 3 * sizeof(uint32_t) + sizeof(gpu::vec4) * ((l.lean_contacts ? 3 : 4) + (l.rolling_springs ? 2 : 0));
}

// One kernel launch: `groups` workgroups, or the indirect arguments at control word
// `indirect_word` (>= 0). Scan dispatches carry a ScanPush instead of a SimPush.
struct Dispatch {
  KernelId kernel = KernelId::KickDrift;
  uint32_t groups = 0;
  int32_t indirect_word = -1;
  gpu::SimPush sim{};
  gpu::ScanPush scan{};
};

// The state that survives between steps, as host arrays (the used part of the contact list).
struct HostState {
  std::vector<gpu::vec4> pos, vel, omega, force, torque, pos_at_build;
  std::vector<uint32_t> control;
  std::vector<uint32_t> row_start, partner, owner, trans_start, trans_list;
  std::vector<gpu::vec4> history;
  std::vector<gpu::vec4> rolling_spring;  // one per contact with rolling springs, else empty
  std::vector<gpu::Body> bodies;  // empty without bodies
};

// Seconds spent per kernel, summed over the dispatches timed.
using KernelTimes = std::map<std::string, double>;

class Backend {
 public:
  virtual ~Backend() = default;
  virtual std::string describe() const = 0;
  // Creates every buffer for `layout` (dropping the previous ones) and uploads constants.
  virtual void allocate(const Layout& layout, const ConstantData& constants) = 0;
  virtual void upload_state(const HostState& s) = 0;
  virtual void download_state(HostState& s) = 0;
  // layout.batch_steps * n_walls states, step-major.
  virtual void upload_walls(const std::vector<gpu::WallState>& walls) = 0;
  // Runs the dispatches in order, each seeing the previous one's writes, and waits.
  // With `times`, adds each kernel's duration (for `repose bench`).
  virtual void execute(const std::vector<Dispatch>& program, KernelTimes* times = nullptr) = 0;
  virtual std::vector<uint32_t> read_control() = 0;
  // Force on each wall from the current contact forces.
  virtual std::vector<gpu::vec4> wall_forces(const gpu::SimPush& push) = 0;
  // Bytes of device (or, for the CPU twin, host) memory held by the simulation buffers.
  virtual size_t memory_bytes() const = 0;
};

}  // namespace repose
