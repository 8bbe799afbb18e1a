#include "vk/kernel_set.h"

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "util/parallel_each.h"
#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/embedded_shaders.h"
#include "vk/spirv_patch.h"
#include "vk/vk_check.h"

namespace repose::vk {

static constexpr uint32_t kPushBytes = 128;

PipelineLibrary::PipelineLibrary(Context& ctx) : ctx_(ctx) {
  VkDevice dev = ctx.device();
  if (ctx.info().max_storage_buffers < gpu::kBindingCount)
    throw VulkanError("device '" + ctx.info().name + "' allows " +
                      std::to_string(ctx.info().max_storage_buffers) +
                      " storage buffers per stage; Repose needs " +
                      std::to_string(gpu::kBindingCount));
  std::vector<VkDescriptorSetLayoutBinding> bindings(gpu::kBindingCount);
  for (uint32_t b = 0; b < gpu::kBindingCount; ++b) {
    bindings[b].binding = b;
    bindings[b].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[b].descriptorCount = 1;
    bindings[b].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  }
  VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  li.bindingCount = gpu::kBindingCount;
  li.pBindings = bindings.data();
  VK_CHECK(vkCreateDescriptorSetLayout(dev, &li, nullptr, &set_layout_));

  VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, kPushBytes};
  VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pli.setLayoutCount = 1;
  pli.pSetLayouts = &set_layout_;
  pli.pushConstantRangeCount = 1;
  pli.pPushConstantRanges = &range;
  VK_CHECK(vkCreatePipelineLayout(dev, &pli, nullptr, &layout_));

  for (uint32_t k = 0; k < static_cast<uint32_t>(KernelId::Count); ++k) {
    const EmbeddedShader& spv = embedded_shader(kernel_shader_name(static_cast<KernelId>(k)));
    std::vector<uint32_t> patched;
    if (ctx.info().denorm_preserve32) patched = with_denormals_preserved(spv.words, spv.bytes / 4);
    VkShaderModuleCreateInfo mi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    mi.codeSize = patched.empty() ? spv.bytes : patched.size() * 4;
    mi.pCode = patched.empty() ? spv.words : patched.data();
    VkShaderModule module;
    VK_CHECK(vkCreateShaderModule(dev, &mi, nullptr, &module));
    modules_.push_back(module);
  }
}

PipelineLibrary::~PipelineLibrary() {
  VkDevice dev = ctx_.device();
  for (auto& p : pipelines_) vkDestroyPipeline(dev, p.second, nullptr);
  for (auto m : modules_) vkDestroyShaderModule(dev, m, nullptr);
  if (layout_) vkDestroyPipelineLayout(dev, layout_, nullptr);
  if (set_layout_) vkDestroyDescriptorSetLayout(dev, set_layout_, nullptr);
}

PipelineLibrary::Key PipelineLibrary::key(KernelId id, uint32_t workgroup, uint32_t flags, uint32_t absent_wall_kinds) {
  // The scan and the wall reduction are written for their own fixed workgroup size.
  uint32_t wg = id == KernelId::Scan         ? gpu::kScanWorkgroup
                : id == KernelId::WallReduce ? gpu::kWallReduceWorkgroup
                                             : workgroup;
  return {static_cast<uint32_t>(id), wg, flags, absent_wall_kinds};
}

VkPipeline PipelineLibrary::create(const Key& key) const {
  const auto [id, wg, flags, absent_wall_kinds] = key;
  // constant_id 0: the workgroup size; 1: the flags word; 2: the absent wall kinds; 3: how / and
  // sqrt are rounded (kernels/glsl_prelude.glsl).
  const uint32_t values[4] = {wg, flags, absent_wall_kinds, ctx_.rounding()};
  const VkSpecializationMapEntry entries[4] = {{0, 0, sizeof(uint32_t)},
                                               {1, sizeof(uint32_t), sizeof(uint32_t)},
                                               {2, 2 * sizeof(uint32_t), sizeof(uint32_t)},
                                               {3, 3 * sizeof(uint32_t), sizeof(uint32_t)}};
  VkSpecializationInfo spec{4, entries, sizeof(values), values};
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  ci.stage.module = modules_[id];
  ci.stage.pName = "main";
  ci.stage.pSpecializationInfo = &spec;
  ci.layout = layout_;
  VkPipeline p;
  VK_CHECK(vkCreateComputePipelines(ctx_.device(), VK_NULL_HANDLE, 1, &ci, nullptr, &p));
  return p;
}

VkPipeline PipelineLibrary::pipeline(const Key& key, double& created_seconds) {
  std::lock_guard<std::mutex> hold(mutex_);  // simulations on several threads share the library
  auto found = pipelines_.find(key);
  if (found != pipelines_.end()) return found->second;
  const auto start = std::chrono::steady_clock::now();
  VkPipeline p = create(key);
  created_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  pipelines_.emplace(key, p);
  return p;
}

void PipelineLibrary::prepare(std::vector<Key> keys) {
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  {
    std::lock_guard<std::mutex> hold(mutex_);
    keys.erase(std::remove_if(keys.begin(), keys.end(), [&](const Key& k) { return pipelines_.count(k) > 0; }),
               keys.end());
  }
  // The driver compiles them side by side (the Vulkan device is not externally synchronised for
  // pipeline creation); those made are kept even if one fails.
  std::vector<VkPipeline> made(keys.size(), VK_NULL_HANDLE);
  auto keep_made = [&] {
    std::lock_guard<std::mutex> hold(mutex_);
    for (size_t i = 0; i < keys.size(); ++i) {
      if (made[i] == VK_NULL_HANDLE) continue;
      if (!pipelines_.emplace(keys[i], made[i]).second) vkDestroyPipeline(ctx_.device(), made[i], nullptr);
    }
  };
  try {
    parallel_each(keys.size(), std::max(1u, std::thread::hardware_concurrency()),
                  [&](size_t i) { made[i] = create(keys[i]); });
  } catch (...) {
    keep_made();
    throw;
  }
  keep_made();
}

size_t PipelineLibrary::size() {
  std::lock_guard<std::mutex> hold(mutex_);
  return pipelines_.size();
}

KernelSet::KernelSet(Context& ctx, uint32_t workgroup)
    : ctx_(ctx), library_(ctx.pipelines()), workgroup_(workgroup) {
  VkDevice dev = ctx.device();
  VkDescriptorPoolSize ps{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, gpu::kBindingCount};
  VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pi.maxSets = 1;
  pi.poolSizeCount = 1;
  pi.pPoolSizes = &ps;
  VK_CHECK(vkCreateDescriptorPool(dev, &pi, nullptr, &pool_));
  VkDescriptorSetLayout set_layout = library_.set_layout();
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &set_layout;
  VK_CHECK(vkAllocateDescriptorSets(dev, &ai, &set_));
}

KernelSet::~KernelSet() {
  if (pool_) vkDestroyDescriptorPool(ctx_.device(), pool_, nullptr);
}

void KernelSet::bind(const std::array<const Buffer*, gpu::kBindingCount>& buffers) {
  std::vector<VkDescriptorBufferInfo> infos(gpu::kBindingCount);
  std::vector<VkWriteDescriptorSet> writes(gpu::kBindingCount);
  for (uint32_t b = 0; b < gpu::kBindingCount; ++b) {
    if (!buffers[b]) throw std::logic_error("KernelSet::bind: binding " + std::to_string(b) + " unset");
    infos[b] = {buffers[b]->handle(), 0, VK_WHOLE_SIZE};
    writes[b] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[b].dstSet = set_;
    writes[b].dstBinding = b;
    writes[b].descriptorCount = 1;
    writes[b].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[b].pBufferInfo = &infos[b];
  }
  vkUpdateDescriptorSets(ctx_.device(), gpu::kBindingCount, writes.data(), 0, nullptr);
}

// The words of a kernel's push constants that specialise its pipeline or shape its dispatch (a
// scan's push has none of them).
struct PushWords {
  uint32_t flags = 0, absent_wall_kinds = 0, max_x = gpu::kMaxGroupsX;
};
static PushWords push_words(KernelId k, const void* push) {
  PushWords w;
  if (k == KernelId::Scan) return w;
  const char* bytes = static_cast<const char*>(push);
  std::memcpy(&w.flags, bytes + offsetof(gpu::SimPush, flags), sizeof w.flags);
  std::memcpy(&w.absent_wall_kinds, bytes + offsetof(gpu::SimPush, absent_wall_kinds), sizeof w.absent_wall_kinds);
  std::memcpy(&w.max_x, bytes + offsetof(gpu::SimPush, max_groups_x), sizeof w.max_x);
  return w;
}

void KernelSet::prepare(const std::vector<std::pair<KernelId, const void*>>& dispatches) {
  std::vector<PipelineLibrary::Key> keys;
  for (const auto& [k, push] : dispatches) {
    const PushWords w = push_words(k, push);
    keys.push_back(PipelineLibrary::key(k, workgroup_, w.flags, w.absent_wall_kinds));
  }
  library_.prepare(std::move(keys));
}

void KernelSet::record(VkCommandBuffer cb, KernelId k, const void* push, uint32_t push_bytes,
                       uint32_t groups, VkBuffer indirect, VkDeviceSize indirect_offset) {
  if (push_bytes > kPushBytes) throw std::logic_error("push constants too large");
  // The pipeline specialised for the push's own words, so the two never disagree.
  const PushWords w = push_words(k, push);
  VkPipeline pipeline =
      library_.pipeline(PipelineLibrary::key(k, workgroup_, w.flags, w.absent_wall_kinds), creation_seconds_);
  vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
  vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, library_.layout(), 0, 1, &set_, 0, nullptr);
  vkCmdPushConstants(cb, library_.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes, push);
  if (indirect != VK_NULL_HANDLE)
    vkCmdDispatchIndirect(cb, indirect, indirect_offset);
  else if (groups > 0)  // in rows of at most max_x groups (invocation_index() counts across them)
    vkCmdDispatch(cb, gpu::dispatch_columns(groups, w.max_x), gpu::dispatch_rows(groups, w.max_x), 1);
}

void KernelSet::barrier(VkCommandBuffer cb) {
  VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  mb.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  mb.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                     VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT;
  vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT |
                           VK_PIPELINE_STAGE_TRANSFER_BIT,
                       0, 1, &mb, 0, nullptr, 0, nullptr);
}

}  // namespace repose::vk
