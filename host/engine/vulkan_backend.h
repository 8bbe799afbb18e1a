// The Vulkan backend: one device buffer per binding of shaders/repose_shared.h, the kernels of
// KernelSet, and a whole dispatch program recorded into one command buffer per call (a submit
// costs ~150 us on lavapipe, so a batch of steps goes in one submit).
#pragma once
#include <array>
#include <memory>

#include "engine/backend.h"
#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/kernel_set.h"

namespace repose {

// Why the device cannot hold or dispatch a simulation of this layout (a buffer above its storage
// range or allocation size, more memory than its device-local heap, too many workgroups), or ""
// when it can. VulkanBackend refuses such a layout; engine/memory_need.h asks before a run.
std::string vulkan_fit_problem(const vk::DeviceInfo& device, const Layout& layout);

class VulkanBackend : public Backend {
 public:
  VulkanBackend(int device_index, uint32_t workgroup);
  ~VulkanBackend() override;
  std::string describe() const override;
  void allocate(const Layout& layout, const ConstantData& constants) override;
  void upload_constants(const ConstantData& constants) override;
  void upload_state(const HostState& s) override;
  void read_binding(uint32_t binding, void* dst, size_t bytes) override { buffers_[binding].download(dst, bytes); }
  void upload_walls(const std::vector<gpu::WallState>& rows, size_t first) override;
  void prepare(const std::vector<Dispatch>& program) override;
  void execute(const std::vector<Dispatch>& program, ExecuteTimes* times) override;
  std::vector<uint32_t> read_control() override;
  std::vector<gpu::vec4> wall_forces(const gpu::SimPush& push) override;
  std::vector<gpu::vec4> contact_forces(uint32_t contacts) override;
  std::vector<gpu::vec4> wall_sums() override;
  size_t memory_bytes() const override;

  vk::Context& context() { return *ctx_; }
  // The first `bytes` of binding b's buffer (kernel tests set raw buffers from the twin's).
  void write_binding(uint32_t binding, const void* src, size_t bytes) { buffers_[binding].upload(src, bytes); }
  uint64_t validation_messages() const { return ctx_->validation_messages(); }


 protected:
  void read_state(HostState& s) override;

 private:
  vk::Buffer& b(uint32_t binding) { return buffers_[binding]; }
  void check_fits(const Layout& l) const;
  std::shared_ptr<vk::Context> ctx_;  // shared by the process's simulations (vk::Context::open)
  vk::KernelSet kernels_;
  Layout layout_;
  std::array<vk::Buffer, gpu::kBindingCount> buffers_;
  VkQueryPool queries_ = VK_NULL_HANDLE;
  uint32_t query_capacity_ = 0;
};

}  // namespace repose
