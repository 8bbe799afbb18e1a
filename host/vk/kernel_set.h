// The compute pipelines and the descriptor set of one simulation: every kernel sees the same
// storage-buffer bindings (shaders/repose_shared.h) and one push-constant block. Workgroup size is
// a specialisation constant, so a variant changes it without a new shader; so are the push
// constants' flags word and absent wall kinds, so that lavapipe does not run the code of
// switched-off features (docs/engineering.md, "lavapipe speed"): one pipeline per kernel and pair
// of words. The pipelines are the device's (PipelineLibrary), created once per process.
#pragma once
#include <array>
#include <map>
#include <mutex>
#include <tuple>
#include <utility>
#include <vector>
#include <vulkan/vulkan.h>

#include "kernel_ids.h"
#include "repose_shared.h"

namespace repose::vk {

class Context;
class Buffer;

// The pipelines of one device, created on first use and kept for every simulation the process
// runs on it: the driver compiles each (lavapipe took 1.2 s for a run's 19, 0.5 s the longest),
// and a test binary or a calibration builds many simulations. Thread-safe.
class PipelineLibrary {
 public:
  explicit PipelineLibrary(Context& ctx);
  ~PipelineLibrary();
  PipelineLibrary(const PipelineLibrary&) = delete;
  PipelineLibrary& operator=(const PipelineLibrary&) = delete;

  VkDescriptorSetLayout set_layout() const { return set_layout_; }
  VkPipelineLayout layout() const { return layout_; }
  // A pipeline: kernel id, workgroup size, flags word, absent wall kinds.
  using Key = std::tuple<uint32_t, uint32_t, uint32_t, uint32_t>;
  // Kernel `id` at `workgroup` invocations (the scan and the wall reduction: their own), specialised
  // for the two words.
  static Key key(KernelId id, uint32_t workgroup, uint32_t flags, uint32_t absent_wall_kinds);
  // The pipeline of `key`; the seconds spent creating it, when this call does, go into created_seconds.
  VkPipeline pipeline(const Key& key, double& created_seconds);
  // Creates those of `keys` not made yet, several at once (one thread per processor).
  void prepare(std::vector<Key> keys);
  size_t size();  // pipelines created so far

 private:
  VkPipeline create(const Key& key) const;
  Context& ctx_;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  std::vector<VkShaderModule> modules_;
  std::mutex mutex_;
  std::map<Key, VkPipeline> pipelines_;
};

class KernelSet {
 public:
  KernelSet(Context& ctx, uint32_t workgroup);
  ~KernelSet();
  KernelSet(const KernelSet&) = delete;
  KernelSet& operator=(const KernelSet&) = delete;

  // Points binding b at buffers[b] (all kBindingCount of them).
  void bind(const std::array<const Buffer*, gpu::kBindingCount>& buffers);

  // Records a dispatch: `groups` workgroups, or the three words at `indirect_offset` bytes of
  // `indirect` when it is non-null. push is copied into the push-constant block.
  void record(VkCommandBuffer cb, KernelId k, const void* push, uint32_t push_bytes,
              uint32_t groups, VkBuffer indirect = VK_NULL_HANDLE, VkDeviceSize indirect_offset = 0);
  // Creates the pipelines of these dispatches (kernel and push constants) that the device has not
  // made yet, side by side, so that the batches find them made.
  void prepare(const std::vector<std::pair<KernelId, const void*>>& dispatches);
  // A full memory barrier between dependent dispatches (shader writes -> reads, indirect args).
  static void barrier(VkCommandBuffer cb);
  uint32_t workgroup() const { return workgroup_; }
  // Seconds spent creating pipelines (the driver compiling a kernel on its first use in the
  // process) since the last call.
  double take_creation_seconds() { return std::exchange(creation_seconds_, 0.0); }

 private:
  Context& ctx_;
  PipelineLibrary& library_;
  uint32_t workgroup_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  double creation_seconds_ = 0;
};

}  // namespace repose::vk
