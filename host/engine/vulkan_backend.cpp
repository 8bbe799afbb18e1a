#include "engine/vulkan_backend.h"

#include <algorithm>
#include <chrono>

#include "engine/buffer_table.h"
#include "engine/step_program.h"
#include "util/memory_info.h"
#include "vk/vk_check.h"

namespace repose {

using namespace gpu;

VulkanBackend::VulkanBackend(int device_index, uint32_t workgroup)
    : ctx_(vk::Context::open(device_index)), kernels_(*ctx_, workgroup) {}

VulkanBackend::~VulkanBackend() {
  if (queries_) vkDestroyQueryPool(ctx_->device(), queries_, nullptr);
}

std::string VulkanBackend::describe() const {
  return "vulkan (" + ctx_->info().name + ", " + ctx_->info().driver + ")";
}

template <class T>
static void up(vk::Buffer& dst, const std::vector<T>& src) {
  dst.upload(src.data(), std::min(src.size() * sizeof(T), dst.size()));
}

template <class T>
static void down(const vk::Buffer& src, std::vector<T>& dst, size_t count) {
  dst.resize(count);
  src.download(dst.data(), count * sizeof(T));
}

std::string vulkan_fit_problem(const vk::DeviceInfo& d, const Layout& l) {
  size_t total = 0;
  for (uint32_t i = 0; i < kBindingCount; ++i) {
    size_t bytes = binding_bytes(i, l);
    total += bytes;
    if (bytes > d.max_storage_range || (d.max_allocation && bytes > d.max_allocation))
      return std::string("buffer ") + kBufferTable[i].name + " needs " + format_bytes(double(bytes)) + ", above what '" +
             d.name + "' binds as one storage buffer (" + d.limits_text() + ")";
  }
  if (d.device_local_bytes && total > d.device_local_bytes)
    return "needs " + format_bytes(double(total)) + " of device memory, " + format_bytes(double(d.device_local_bytes)) +
           " available on '" + d.name + "'";
  // The largest dispatch: one invocation per particle, bucket or contact-list entry.
  uint64_t most = std::max<uint64_t>({uint64_t(l.n_particles) + 1, uint64_t(l.table_size) + 2, l.capacity, l.n_walls});
  uint32_t groups = uint32_t((most + gpu::kDefaultWorkgroup - 1) / gpu::kDefaultWorkgroup);
  if (max_groups_x() > d.max_groups[0] || gpu::dispatch_rows(groups, max_groups_x()) > d.max_groups[1])
    return "'" + d.name + "' cannot dispatch " + std::to_string(groups) + " workgroups (" + d.limits_text() + ")";
  return "";
}

// Refuses a layout the device cannot hold or dispatch, before anything is allocated.
void VulkanBackend::check_fits(const Layout& l) const {
  std::string problem = vulkan_fit_problem(ctx_->info(), l);
  if (!problem.empty()) throw vk::VulkanError(problem);
}

void VulkanBackend::allocate(const Layout& l, const ConstantData& constants) {
  check_fits(l);
  layout_ = l;
  std::array<const vk::Buffer*, kBindingCount> bound{};
  for (uint32_t i = 0; i < kBindingCount; ++i) {
    size_t bytes = binding_bytes(i, l);
    VkBufferUsageFlags extra = i == kBindControl ? VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT : 0;
    buffers_[i] = vk::Buffer();
    buffers_[i] = vk::Buffer(*ctx_, std::max<size_t>(bytes, 16), extra);
    bound[i] = &buffers_[i];
  }
  // Zero everything once so no kernel ever reads uninitialised memory.
  ctx_->submit_and_wait([&](VkCommandBuffer cb) {
    for (auto& buf : buffers_)
      if (buf.handle() != VK_NULL_HANDLE) vkCmdFillBuffer(cb, buf.handle(), 0, VK_WHOLE_SIZE, 0);
  });
  upload_constants(constants);
  kernels_.bind(bound);
}

void VulkanBackend::upload_constants(const ConstantData& constants) {
  for_each_constant(constants, [&](const BufferSpec& spec, const auto& v) { up(b(spec.binding), v); });
}

void VulkanBackend::upload_state(const HostState& s) {
  for_each_kept(s, [&](const BufferSpec& spec, const auto& v) { up(b(spec.binding), v); });
}

void VulkanBackend::read_state(HostState& s) {
  for_each_kept(s, [&](const BufferSpec& spec, auto& v) { down(b(spec.binding), v, used_elements(spec, layout_, s)); });
}

void VulkanBackend::upload_walls(const std::vector<WallState>& rows, size_t first) {
  vk::Buffer& dst = b(kBindWalls);
  size_t offset = std::min(first * sizeof(WallState), dst.size());
  dst.upload(rows.data(), std::min(rows.size() * sizeof(WallState), dst.size() - offset), offset);
}

// A dispatch's push constants: a scan's ScanPush, every other kernel's SimPush.
static const void* push_of(const Dispatch& d) {
  return d.kernel == KernelId::Scan ? static_cast<const void*>(&d.scan) : static_cast<const void*>(&d.sim);
}

void VulkanBackend::prepare(const std::vector<Dispatch>& program) {
  std::vector<std::pair<KernelId, const void*>> dispatches;
  for (const Dispatch& d : program) dispatches.push_back({d.kernel, push_of(d)});
  kernels_.prepare(dispatches);
}

void VulkanBackend::execute(const std::vector<Dispatch>& program, ExecuteTimes* times) {
  uint32_t needed = times ? uint32_t(program.size()) * 2 : 0;
  if (times && needed > query_capacity_) {
    if (queries_) vkDestroyQueryPool(ctx_->device(), queries_, nullptr);
    VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qi.queryCount = needed;
    VK_CHECK(vkCreateQueryPool(ctx_->device(), &qi, nullptr, &queries_));
    query_capacity_ = needed;
  }
  VkBuffer control = b(kBindControl).handle();
  ctx_->submit_and_wait([&](VkCommandBuffer cb) {
    const auto record_start = std::chrono::steady_clock::now();
    kernels_.take_creation_seconds();  // pipelines created before (untimed) are not this batch's
    if (times) vkCmdResetQueryPool(cb, queries_, 0, needed);
    uint32_t q = 0;
    for (const Dispatch& d : program) {
      if (times) vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, q++);
      const void* push = push_of(d);
      uint32_t bytes = d.kernel == KernelId::Scan ? sizeof(ScanPush) : sizeof(SimPush);
      if (d.indirect_word >= 0)
        kernels_.record(cb, d.kernel, push, bytes, 0, control, d.indirect_word * sizeof(uint32_t));
      else
        kernels_.record(cb, d.kernel, push, bytes, d.groups);
      vk::KernelSet::barrier(cb);
      if (times) vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, q++);
    }
    if (times) {
      const double created = kernels_.take_creation_seconds();
      times->device.pipelines += created;
      times->device.recording +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - record_start).count() - created;
    }
  });
  if (times) {
    std::vector<uint64_t> stamps(needed);
    VK_CHECK(vkGetQueryPoolResults(ctx_->device(), queries_, 0, needed, needed * sizeof(uint64_t),
                                   stamps.data(), sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(ctx_->physical(), &props);
    double period = props.limits.timestampPeriod * 1e-9, in_kernels = 0;
    for (size_t i = 0; i < program.size(); ++i) {
      double seconds = double(stamps[2 * i + 1] - stamps[2 * i]) * period;
      times->kernels[kernel_shader_name(program[i].kernel)] += seconds;
      in_kernels += seconds;
    }
    if (needed > 0) times->device.between_kernels += std::max(0.0, double(stamps[needed - 1] - stamps[0]) * period - in_kernels);
  }
}

std::vector<uint32_t> VulkanBackend::read_control() {
  std::vector<uint32_t> c;
  down(b(kBindControl), c, kControlWords);
  return c;
}

std::vector<vec4> VulkanBackend::wall_forces(const SimPush& push) {
  if (layout_.n_wall_groups == 0) return {};
  Dispatch d;
  d.kernel = KernelId::WallReduce;
  d.groups = layout_.n_wall_groups;
  d.sim = push;
  execute({d}, nullptr);
  std::vector<vec4> f;
  down(b(kBindWallForce), f, layout_.n_wall_groups);
  return f;
}

std::vector<vec4> VulkanBackend::wall_sums() {
  std::vector<vec4> all;
  down(b(kBindWallForce), all, 3 * size_t(layout_.n_wall_groups));
  return std::vector<vec4>(all.begin() + layout_.n_wall_groups, all.end());
}

std::vector<vec4> VulkanBackend::contact_forces(uint32_t contacts) {
  std::vector<vec4> f;
  down(b(kBindContactForce), f, std::min(contacts, layout_.capacity));
  return f;
}

size_t VulkanBackend::memory_bytes() const {
  size_t total = 0;
  for (const auto& buf : buffers_) total += buf.size();
  return total;
}

}  // namespace repose
