// What the simulation driver needs from a compute backend. Two implement it: the Vulkan one
// (shaders on any Vulkan device, lavapipe included) and the CPU twin (the same kernels in C++).
// Both execute the same dispatch programs (step_program.h), so they produce the same bytes.
#pragma once
#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "kernel_ids.h"
#include "repose_shared.h"

namespace repose {

// The backend a run takes when its caller names none: commands a user runs (`repose run`,
// `repose experiment`) the fastest here ("auto": resolve_backend, engine/backend_factory.h); runs the
// library makes (calibration campaigns, diagnosis searches, tests) one thread of the cpu backend
// each, so that many run side by side on the cores.
inline constexpr const char* kUserBackend = "auto";
inline constexpr const char* kLibraryBackend = "cpu";

// Buffer sizes of one simulation.
struct Layout {
  uint32_t n_particles = 0;
  uint32_t n_walls = 0;
  uint32_t n_moving_walls = 0;  // walls with a prescribed motion (a row each per step of a batch)
  uint32_t n_wall_groups = 0;   // named walls (wall_reduce's sums)
  uint32_t wall_grid_words = 0; // the wall grid (Model::wall_grid; 0: none)
  uint32_t n_materials = 0;
  uint32_t table_size = 0;
  uint32_t capacity = 0;     // contact list entries
  uint32_t n_bodies = 0;     // rigid bodies; 0: every particle is a free sphere
  uint32_t n_parts = 0;      // the bodies' parts (broad phase; gpu::BodyPart)
  uint32_t batch_steps = 1;  // wall states per upload
  bool lean_contacts = false;  // no torque_j buffer (KernelVariant::lean)
  bool rolling_springs = false;  // kFlagRollingSpring: a rolling spring per contact (and the old list's)
};

// Inputs that stay constant during a run, uploaded with every allocation: the table's
// Constant rows (shaders/repose_shared.h; subs is empty without bodies).
struct ConstantData {
#define REPOSE_CONSTANT_MEMBER(binding, Name, name, type, count, need, keep) REPOSE_CONSTANT_##keep(type, name)
#define REPOSE_CONSTANT_Constant(type, name) std::vector<gpu::type> name;
#define REPOSE_CONSTANT_State(type, name)
#define REPOSE_CONSTANT_File(type, name)
#define REPOSE_CONSTANT_Scratch(type, name)
#define REPOSE_CONSTANT_Walls(type, name)
  REPOSE_BUFFERS(REPOSE_CONSTANT_MEMBER)
};

// One kernel launch: `groups` workgroups, or the indirect arguments at control word
// `indirect_word` (>= 0). Scan dispatches carry a ScanPush instead of a SimPush.
struct Dispatch {
  KernelId kernel = KernelId::KickDrift;
  uint32_t groups = 0;
  int32_t indirect_word = -1;
  gpu::SimPush sim{};
  gpu::ScanPush scan{};
};

// The state that survives between steps, as host arrays: one vector per State or File row of
// the buffer table, named as the binding (pos, vel, ..., partner, history, bodies, ...), holding
// the used part (contacts in the list, particles, bodies; empty when the case does not need it).
struct HostState {
#define REPOSE_STATE_MEMBER(binding, Name, name, type, count, need, keep) REPOSE_STATE_##keep(type, name)
#define REPOSE_STATE_State(type, name) std::vector<gpu::type> name;
#define REPOSE_STATE_File(type, name) std::vector<gpu::type> name;
#define REPOSE_STATE_Constant(type, name)
#define REPOSE_STATE_Scratch(type, name)
#define REPOSE_STATE_Walls(type, name)
  REPOSE_BUFFERS(REPOSE_STATE_MEMBER)
};

// Seconds spent per kernel, summed over the dispatches timed.
using KernelTimes = std::map<std::string, double>;

// What a device's batches spent besides their kernels, in seconds: creating pipelines (the driver
// compiling each kernel on its first use), the rest of recording the commands on the host, and the
// device's time from a batch's first kernel's start to its last one's end that no kernel took (the
// barriers between kernels and each launch). Zeros on the cpu backend, which has no device.
struct DeviceOverheads {
  double pipelines = 0;
  double recording = 0;
  double between_kernels = 0;
  double total() const { return pipelines + recording + between_kernels; }
  void add(const DeviceOverheads& o) {
    pipelines += o.pipelines;
    recording += o.recording;
    between_kernels += o.between_kernels;
  }
};

// A timed execute's seconds: each kernel's, and the batch's device overheads.
struct ExecuteTimes {
  KernelTimes kernels;
  DeviceOverheads device;
};

class Backend {
 public:
  virtual ~Backend() = default;
  virtual std::string describe() const = 0;
  // Creates every buffer for `layout` (dropping the previous ones) and uploads constants.
  virtual void allocate(const Layout& layout, const ConstantData& constants) = 0;
  // Replaces the constants of the current buffers (a new particle order); the rest is kept.
  virtual void upload_constants(const ConstantData& constants) = 0;
  virtual void upload_state(const HostState& s) = 0;
  // The whole state into s (its used part). Simulation calls it only when something reads the
  // state; state_downloads() counts the calls, so tests can tell a batch nobody read from one read.
  void download_state(HostState& s) {
    ++state_downloads_;
    read_state(s);
  }
  uint64_t state_downloads() const { return state_downloads_; }
  // The first `bytes` of one buffer, alone (rows in the device's slots): what a check whose answer
  // does not depend on the order reads (Simulation::rows_in_any_order), and the twin tests.
  virtual void read_binding(uint32_t binding, void* dst, size_t bytes) = 0;
  // Wall rows from row `first` (walls.h wall_at): every wall's (first 0), or the moving walls'
  // at each step of a batch, step-major (first n_walls).
  virtual void upload_walls(const std::vector<gpu::WallState>& rows, size_t first) = 0;
  // Gets ready to run these dispatches (a device compiles their kernels, several at once), so that
  // the batches do not wait for it one kernel at a time; optional.
  virtual void prepare(const std::vector<Dispatch>& /*program*/) {}
  // Runs the dispatches in order, each seeing the previous one's writes, and waits.
  // With `times`, adds to it each kernel's duration and the batch's other times (ExecuteTimes).
  virtual void execute(const std::vector<Dispatch>& program, ExecuteTimes* times = nullptr) = 0;
  virtual std::vector<uint32_t> read_control() = 0;
  // Force on each named wall from the current contact forces.
  virtual std::vector<gpu::vec4> wall_forces(const gpu::SimPush& push) = 0;
  // The wall_reduce sums (store_wall_force): per named wall its running force sum, then its peak.
  virtual std::vector<gpu::vec4> wall_sums() = 0;
  // The last step's force on the owner of each of the list's first `contacts` entries.
  virtual std::vector<gpu::vec4> contact_forces(uint32_t contacts) = 0;
  // Bytes of device (or, for the CPU twin, host) memory held by the simulation buffers.
  virtual size_t memory_bytes() const = 0;
  // Threads the host may give its own work on the state (turning it between slots and global
  // ids): the cpu backend's, every processor beside a device, which steps without them.
  virtual unsigned host_threads() const { return std::max(1u, std::thread::hardware_concurrency()); }

 protected:
  virtual void read_state(HostState& s) = 0;

 private:
  uint64_t state_downloads_ = 0;
};

}  // namespace repose
