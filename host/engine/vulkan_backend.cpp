#include "engine/vulkan_backend.h"

#include <algorithm>

#include "vk/vk_check.h"

namespace repose {

using namespace gpu;

VulkanBackend::VulkanBackend(int device_index, uint32_t workgroup)
    : ctx_(device_index), kernels_(ctx_, workgroup) {}

VulkanBackend::~VulkanBackend() {
  if (queries_) vkDestroyQueryPool(ctx_.device(), queries_, nullptr);
}

std::string VulkanBackend::describe() const {
  return "vulkan (" + ctx_.info().name + ", " + ctx_.info().driver + ")";
}

void VulkanBackend::allocate(const Layout& l, const ConstantData& constants) {
  const auto& material = constants.material;
  const auto& pairs = constants.pairs;
  layout_ = l;
  size_t n = l.n_particles, c = std::max<uint32_t>(l.capacity, 1), t = l.table_size;
  size_t v4 = sizeof(vec4), u = sizeof(uint32_t);
  size_t sizes[kBindingCount] = {};
  sizes[kBindPos] = sizes[kBindVel] = sizes[kBindOmega] = sizes[kBindForce] = sizes[kBindTorque] =
      sizes[kBindPosAtBuild] = n * v4;
  sizes[kBindMaterial] = n * u;
  sizes[kBindPairs] = pairs.size() * sizeof(PairParams);
  sizes[kBindWalls] = std::max<size_t>(size_t(l.batch_steps) * l.n_walls, 1) * sizeof(WallState);
  sizes[kBindControl] = kControlWords * u;
  sizes[kBindCellOf] = n * u;
  sizes[kBindCellStart] = (t + 2) * u;
  sizes[kBindCellFill] = (t + 1) * u;
  sizes[kBindSorted] = n * u;
  sizes[kBindRowStart] = sizes[kBindOldRowStart] = sizes[kBindTransStart] = (n + 1) * u;
  sizes[kBindTransFill] = n * u;
  sizes[kBindPartner] = sizes[kBindOwner] = sizes[kBindTransList] = c * u;
  sizes[kBindHistory] = sizes[kBindContactForce] = sizes[kBindTorqueI] = c * v4;
  sizes[kBindTorqueJ] = l.lean_contacts ? 0 : c * v4;
  sizes[kBindWallForce] = std::max<size_t>(l.n_walls, 1) * v4;
  sizes[kBindBodies] = l.n_bodies * sizeof(Body);
  sizes[kBindSubSpheres] = constants.subs.size() * sizeof(SubSphere);
  sizes[kBindRollingSpring] = l.rolling_springs ? 2 * c * v4 : 0;
  std::array<const vk::Buffer*, kBindingCount> bound{};
  for (uint32_t i = 0; i < kBindingCount; ++i) {
    if (i == kBindOldPartner || i == kBindOldHistory) {
      buffers_[i] = vk::Buffer();  // aliases, bound below
      continue;
    }
    if (sizes[i] > ctx_.info().max_storage_range)
      throw vk::VulkanError("buffer " + std::to_string(i) + " needs " + std::to_string(sizes[i]) +
                            " bytes, above the device's storage-buffer range");
    VkBufferUsageFlags extra = i == kBindControl ? VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT : 0;
    buffers_[i] = vk::Buffer(ctx_, std::max<size_t>(sizes[i], 16), extra);
    bound[i] = &buffers_[i];
  }
  bound[kBindOldPartner] = &buffers_[kBindTransList];
  bound[kBindOldHistory] = &buffers_[kBindContactForce];
  // Zero everything once so no kernel ever reads uninitialised memory.
  ctx_.submit_and_wait([&](VkCommandBuffer cb) {
    for (auto& buf : buffers_)
      if (buf.handle() != VK_NULL_HANDLE) vkCmdFillBuffer(cb, buf.handle(), 0, VK_WHOLE_SIZE, 0);
  });
  b(kBindMaterial).upload(material.data(), material.size() * u);
  b(kBindPairs).upload(pairs.data(), pairs.size() * sizeof(PairParams));
  if (!constants.subs.empty())
    b(kBindSubSpheres).upload(constants.subs.data(), constants.subs.size() * sizeof(SubSphere));
  kernels_.bind(bound);
}

template <class T>
static void up(vk::Buffer& dst, const std::vector<T>& src) {
  dst.upload(src.data(), std::min(src.size() * sizeof(T), dst.size()));
}

void VulkanBackend::upload_state(const HostState& s) {
  up(b(kBindPos), s.pos); up(b(kBindVel), s.vel); up(b(kBindOmega), s.omega);
  up(b(kBindForce), s.force); up(b(kBindTorque), s.torque); up(b(kBindPosAtBuild), s.pos_at_build);
  up(b(kBindControl), s.control); up(b(kBindRowStart), s.row_start); up(b(kBindPartner), s.partner);
  up(b(kBindOwner), s.owner); up(b(kBindTransStart), s.trans_start);
  up(b(kBindTransList), s.trans_list); up(b(kBindHistory), s.history);
  if (layout_.n_bodies) up(b(kBindBodies), s.bodies);
  if (layout_.rolling_springs) up(b(kBindRollingSpring), s.rolling_spring);
}

template <class T>
static void down(const vk::Buffer& src, std::vector<T>& dst, size_t count) {
  dst.resize(count);
  src.download(dst.data(), count * sizeof(T));
}

void VulkanBackend::download_state(HostState& s) {
  size_t n = layout_.n_particles;
  down(b(kBindControl), s.control, kControlWords);
  size_t used = std::min<size_t>(s.control[kCtlContacts], layout_.capacity);
  down(b(kBindPos), s.pos, n); down(b(kBindVel), s.vel, n); down(b(kBindOmega), s.omega, n);
  down(b(kBindForce), s.force, n); down(b(kBindTorque), s.torque, n);
  down(b(kBindPosAtBuild), s.pos_at_build, n);
  down(b(kBindRowStart), s.row_start, n + 1); down(b(kBindTransStart), s.trans_start, n + 1);
  down(b(kBindPartner), s.partner, used); down(b(kBindOwner), s.owner, used);
  down(b(kBindHistory), s.history, used);
  size_t trans_used = std::min<size_t>(s.trans_start[n], layout_.capacity);
  down(b(kBindTransList), s.trans_list, trans_used);
  if (layout_.n_bodies) down(b(kBindBodies), s.bodies, layout_.n_bodies);
  if (layout_.rolling_springs) down(b(kBindRollingSpring), s.rolling_spring, used);
}

void VulkanBackend::upload_walls(const std::vector<WallState>& walls) { up(b(kBindWalls), walls); }

void VulkanBackend::execute(const std::vector<Dispatch>& program, KernelTimes* times) {
  uint32_t needed = times ? uint32_t(program.size()) * 2 : 0;
  if (times && needed > query_capacity_) {
    if (queries_) vkDestroyQueryPool(ctx_.device(), queries_, nullptr);
    VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qi.queryCount = needed;
    VK_CHECK(vkCreateQueryPool(ctx_.device(), &qi, nullptr, &queries_));
    query_capacity_ = needed;
  }
  VkBuffer control = b(kBindControl).handle();
  ctx_.submit_and_wait([&](VkCommandBuffer cb) {
    if (times) vkCmdResetQueryPool(cb, queries_, 0, needed);
    uint32_t q = 0;
    for (const Dispatch& d : program) {
      if (times) vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, q++);
      const void* push = d.kernel == KernelId::Scan ? static_cast<const void*>(&d.scan)
                                                    : static_cast<const void*>(&d.sim);
      uint32_t bytes = d.kernel == KernelId::Scan ? sizeof(ScanPush) : sizeof(SimPush);
      if (d.indirect_word >= 0)
        kernels_.record(cb, d.kernel, push, bytes, 0, control, d.indirect_word * sizeof(uint32_t));
      else
        kernels_.record(cb, d.kernel, push, bytes, d.groups);
      vk::KernelSet::barrier(cb);
      if (times) vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, q++);
    }
  });
  if (times) {
    std::vector<uint64_t> stamps(needed);
    VK_CHECK(vkGetQueryPoolResults(ctx_.device(), queries_, 0, needed, needed * sizeof(uint64_t),
                                   stamps.data(), sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(ctx_.physical(), &props);
    double period = props.limits.timestampPeriod * 1e-9;
    for (size_t i = 0; i < program.size(); ++i)
      (*times)[kernel_shader_name(program[i].kernel)] +=
          double(stamps[2 * i + 1] - stamps[2 * i]) * period;
  }
}

std::vector<uint32_t> VulkanBackend::read_control() {
  std::vector<uint32_t> c;
  down(b(kBindControl), c, kControlWords);
  return c;
}

std::vector<vec4> VulkanBackend::wall_forces(const SimPush& push) {
  if (layout_.n_walls == 0) return {};
  Dispatch d;
  d.kernel = KernelId::WallReduce;
  d.groups = layout_.n_walls;
  d.sim = push;
  execute({d}, nullptr);
  std::vector<vec4> f;
  down(b(kBindWallForce), f, layout_.n_walls);
  return f;
}

size_t VulkanBackend::memory_bytes() const {
  size_t total = 0;
  for (const auto& buf : buffers_) total += buf.size();
  return total;
}

}  // namespace repose
