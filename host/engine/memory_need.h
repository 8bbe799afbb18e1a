// The memory a simulation needs, from the same buffer table the backends allocate from
// (shaders/repose_shared.h), so the figure follows every buffer added there:
// - the backend's buffers: host memory on the cpu backend and on Vulkan devices of the cpu type
//   (lavapipe), device memory on a GPU; the cpu backend's walk rows beside them (check_run_memory);
// - the host's copies: the state the simulation keeps between batches (the contact list counted
//   at its capacity, as it can fill it before it grows), the model, the constants, a batch of
//   wall rows, and a VTK frame while it is written.
// The contact list starts at first_contact_capacity() and grows by a quarter when a run needs
// more (a denser packing, clumps): the figure is then that much low. A run prints it before it
// starts and refuses, with nothing written, when it does not fit (check_memory_fits).
#pragma once
#include <cstddef>
#include <stdexcept>
#include <string>

#include "engine/backend.h"
#include "engine/model.h"
#include "engine/step_program.h"
#include "util/memory_info.h"
#include "vk/context.h"

namespace repose {

struct MemoryNeed {
  Layout layout;
  size_t device_bytes = 0;         // the backend's buffers
  size_t host_bytes = 0;           // the host's copies
  size_t staging_bytes = 0;        // a GPU's transfer buffers in host memory (vk::kStagingBytes)
  bool device_in_host_memory = true;
  // What the run adds to this process's memory: host copies, staging, and the buffers when they are there.
  size_t host_total() const { return host_bytes + staging_bytes + (device_in_host_memory ? device_bytes : 0); }
  // The same split by what it grows with (both add up to host_total()).
  double bytes_per_entry = 0;      // per contact-list entry
  double bytes_per_particle = 0;   // per particle, the rest but staging (buckets, bodies, walls shared out)
  AvailableMemory available;       // what this process may still allocate (check_memory_fits)
};

// frames: VTK frames are written during the run (a frame's arrays while it is written);
// capacity: list entries (0: first_contact_capacity, what a new run starts with).
MemoryNeed memory_need(const Model& m, const KernelVariant& v, uint32_t batch_steps, bool device_in_host_memory,
                       bool frames, uint32_t capacity = 0);

// One line: "needs 1.21 GiB (1000000 particles x 650 B + 6000064 list entries x 104 B), 20.3 GiB
// available"; with the device's share when the buffers are on a GPU.
std::string describe_memory_need(const MemoryNeed& need);

// A run that cannot fit: "needs X GiB, Y available (MemAvailable)".
class MemoryShortfall : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Records what is available in need, and throws MemoryShortfall when host_total() is above what this process may still allocate
// (util/memory_info.h: MemAvailable, the cgroup's limit, ulimit -v), or, with a Vulkan device,
// when the device cannot hold the buffers (vulkan_fit_problem: its heap, buffer range, dispatch
// size).
void check_memory_fits(MemoryNeed& need, const vk::DeviceInfo* device);

// memory_need and check_memory_fits for a run on a backend as resolve_backend names it
// ("cpu", or "vulkan" and a device index, -1 for the default device).
MemoryNeed check_run_memory(const Model& m, const KernelVariant& v, uint32_t batch_steps, const std::string& backend,
                            int device, bool frames, uint32_t capacity = 0);

}  // namespace repose
