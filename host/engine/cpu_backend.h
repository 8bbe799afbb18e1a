// The CPU twin backend: buffers are host memory laid out as on the device, dispatches run the
// C++ kernel bodies on a thread pool. Results are byte-identical to the Vulkan backend's, with
// any thread count.
#pragma once
#include <array>
#include <cstddef>
#include <memory>
#include <vector>

#include "cpu_kernels.h"
#include "engine/backend.h"
#include "thread_pool.h"

namespace repose {

class CpuBackend : public Backend {
 public:
  explicit CpuBackend(unsigned threads);
  std::string describe() const override;
  void allocate(const Layout& layout, const ConstantData& constants) override;
  void upload_constants(const ConstantData& constants) override;
  void upload_state(const HostState& s) override;
  void read_binding(uint32_t binding, void* dst, size_t bytes) override;
  unsigned host_threads() const override { return pool_.size(); }
  void upload_walls(const std::vector<gpu::WallState>& rows, size_t first) override;
  void execute(const std::vector<Dispatch>& program, ExecuteTimes* times) override;
  std::vector<uint32_t> read_control() override;
  std::vector<gpu::vec4> wall_forces(const gpu::SimPush& push) override;
  std::vector<gpu::vec4> contact_forces(uint32_t contacts) override;
  std::vector<gpu::vec4> wall_sums() override;
  size_t memory_bytes() const override;
  // Seconds per contact of the contact law alone on the pool's threads, its rows already in
  // registers (contact_lanes.h; the best of five passes): the bench's compute ceiling for
  // contact_forces. 0 when the lanes do not run this step's contacts.
  double contact_law_seconds_per_contact();
  // Binding b's array (kernel tests compare raw buffers with the Vulkan backend).
  const gpu::Buffers& buffers() const { return buf_; }


 protected:
  void read_state(HostState& s) override;

 private:
  void point_buffers();
  template <class T>
  void put(uint32_t binding, const std::vector<T>& src);
  ThreadPool pool_;
  Layout layout_;
  // Zeroed host memory for every binding at once, aligned to 2 MiB and advised as transparent
  // huge pages when it is that large: the kernels' scattered reads of partners' rows then miss
  // the TLB far less.
  struct FreeArena {
    void operator()(std::byte* p) const;
  };
  static std::unique_ptr<std::byte, FreeArena> zeroed_arena(size_t bytes);
  struct Binding {
    std::byte* begin = nullptr;
    size_t length = 0;
    std::byte* data() const { return begin; }
    size_t size() const { return length; }
  };
  std::unique_ptr<std::byte, FreeArena> arena_;
  // Each binding of the buffer table (none for aliases): its part of the arena.
  std::array<Binding, gpu::kBindingCount> storage_;
  Binding walk_rows_;  // not a binding: Buffers::walk_rows, after the bindings in the arena
  gpu::Buffers buf_;
};

}  // namespace repose
