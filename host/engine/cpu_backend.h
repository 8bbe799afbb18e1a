// The CPU twin backend: buffers are host vectors, dispatches run the C++ kernel bodies on a
// thread pool. Results are byte-identical to the Vulkan backend's, with any thread count.
#pragma once
#include <memory>

#include "cpu_kernels.h"
#include "engine/backend.h"
#include "thread_pool.h"

namespace repose {

class CpuBackend : public Backend {
 public:
  explicit CpuBackend(unsigned threads);
  std::string describe() const override;
  void allocate(const Layout& layout, const ConstantData& constants) override;
  void upload_state(const HostState& s) override;
  void download_state(HostState& s) override;
  void upload_walls(const std::vector<gpu::WallState>& walls) override;
  void execute(const std::vector<Dispatch>& program, KernelTimes* times) override;
  std::vector<uint32_t> read_control() override;
  std::vector<gpu::vec4> wall_forces(const gpu::SimPush& push) override;
  size_t memory_bytes() const override;
  // Binding b's array (kernel tests compare raw buffers with the Vulkan backend).
  const gpu::Buffers& buffers() const { return buf_; }

 private:
  void point_buffers();
  ThreadPool pool_;
  Layout layout_;
  // Storage, one vector per binding.
  // No old_history_ / old_partner_: those bindings alias contact_force_ / trans_list_.
  std::vector<gpu::vec4> pos_, vel_, omega_, force_, torque_, pos_at_build_, history_, rolling_spring_,
      contact_force_, torque_i_, torque_j_, wall_force_;
  std::vector<uint32_t> material_, control_, cell_of_, cell_start_, cell_fill_, sorted_,
      row_start_, partner_, owner_, old_row_start_, trans_start_, trans_fill_, trans_list_;
  std::vector<gpu::PairParams> pairs_;
  std::vector<gpu::WallState> walls_;
  std::vector<gpu::Body> bodies_;
  std::vector<gpu::SubSphere> subs_;
  gpu::Buffers buf_;
};

}  // namespace repose
