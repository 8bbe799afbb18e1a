#include "vk/buffer.h"

#include <algorithm>
#include <cstring>
#include <thread>
#include <utility>

#include "util/parallel_each.h"
#include "vk/context.h"
#include "vk/vk_check.h"

namespace repose::vk {

namespace {

// A transfer of a million grains' state (~0.5 GB each way in a cell-order renewal, README "On a
// GPU") on every host core.
void copy_bytes(void* to, const void* from, size_t bytes) {
  parallel_copy(to, from, bytes, std::max(1u, std::thread::hardware_concurrency()));
}

// A transfer that fits its staging buffer goes whole, in one piece (control words, a batch's wall
// rows, most rows). A larger one goes in pieces through the buffer's two halves in turn: the host
// fills (or empties) one while the device copies the other, where one buffer used whole made each
// wait for the other (a million grains' state crosses the bus in ~16 pieces).
struct StagingSlots {
  size_t count, size;  // one slot where the buffer is a single byte (REPOSE_STAGING=1)
  StagingSlots(size_t staging, size_t transfer)
      : count(transfer > staging && staging >= 2 ? 2 : 1), size(staging / count) {}
};

// The copies a transfer has in flight, one per slot, waited for however the transfer ends (an
// error while one goes must not leave the device writing into a staging buffer reused next).
struct InFlight {
  Context& ctx;
  Context::Submission slot[2];
  ~InFlight() {
    for (auto& s : slot) try {
        ctx.finish(s);
      } catch (...) {  // already failing: the first error is the one to report
      }
  }
};

}  // namespace

Buffer::Buffer(Context& ctx, size_t bytes, VkBufferUsageFlags extra_usage, Memory memory)
    : ctx_(&ctx), bytes_(bytes) {
  VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bi.size = bytes == 0 ? 16 : bytes;  // Vulkan forbids empty buffers
  bi.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
             VK_BUFFER_USAGE_TRANSFER_DST_BIT | extra_usage;
  bi.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VK_CHECK(vkCreateBuffer(ctx.device(), &bi, nullptr, &buffer_));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device(), buffer_, &req);
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = req.size;
  const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  ai.memoryTypeIndex =
      memory == Memory::Device   ? ctx.memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0)
      : memory == Memory::Upload ? ctx.memory_type(req.memoryTypeBits, host, 0)
                                 : ctx.memory_type(req.memoryTypeBits, host, VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
  VkResult r = vkAllocateMemory(ctx.device(), &ai, nullptr, &memory_);
  if (r != VK_SUCCESS) {
    vkDestroyBuffer(ctx.device(), buffer_, nullptr);
    buffer_ = VK_NULL_HANDLE;
    throw_vk_error("vkAllocateMemory", r, __FILE__, __LINE__);
  }
  VK_CHECK(vkBindBufferMemory(ctx.device(), buffer_, memory_, 0));
  // lavapipe's only memory type is device-local, host-visible and cached: map it and skip staging
  // (unless REPOSE_STAGING asks for a discrete GPU's path).
  VkMemoryPropertyFlags flags = ctx.memory_flags(ai.memoryTypeIndex);
  bool map = (flags & host) == host && !(memory == Memory::Device && staging_forced());
  if (map) VK_CHECK(vkMapMemory(ctx.device(), memory_, 0, VK_WHOLE_SIZE, 0, &mapped_));
  cached_ = mapped_ && (flags & VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
}

Buffer::~Buffer() { release(); }

Buffer::Buffer(Buffer&& o) noexcept { *this = std::move(o); }

Buffer& Buffer::operator=(Buffer&& o) noexcept {
  if (this != &o) {
    release();
    std::swap(ctx_, o.ctx_);
    std::swap(buffer_, o.buffer_);
    std::swap(memory_, o.memory_);
    std::swap(mapped_, o.mapped_);
    std::swap(cached_, o.cached_);
    std::swap(bytes_, o.bytes_);
  }
  return *this;
}

void Buffer::release() {
  if (!ctx_) return;
  if (mapped_) vkUnmapMemory(ctx_->device(), memory_);
  if (buffer_) vkDestroyBuffer(ctx_->device(), buffer_, nullptr);
  if (memory_) vkFreeMemory(ctx_->device(), memory_, nullptr);
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
  ctx_ = nullptr;
  bytes_ = 0;
}

void Buffer::upload(const void* data, size_t bytes, size_t offset) {
  if (bytes == 0) return;
  if (mapped_) {
    copy_bytes(static_cast<char*>(mapped_) + offset, data, bytes);
    return;
  }
  std::lock_guard<std::recursive_mutex> hold(ctx_->mutex());  // the staging buffer is shared
  Buffer& staging = ctx_->staging(Memory::Upload, bytes);
  const StagingSlots slots(staging.size(), bytes);
  InFlight copying{*ctx_};
  for (size_t done = 0, k = 0; done < bytes; ++k) {
    const size_t s = k % slots.count, at = s * slots.size, piece = std::min(bytes - done, slots.size);
    ctx_->finish(copying.slot[s]);  // the device has read this slot's last piece
    copy_bytes(static_cast<char*>(staging.mapped()) + at, static_cast<const char*>(data) + done, piece);
    copying.slot[s] = ctx_->submit([&](VkCommandBuffer cb) {
      VkBufferCopy region{at, offset + done, piece};
      vkCmdCopyBuffer(cb, staging.handle(), buffer_, 1, &region);
    });
    done += piece;
  }
  for (auto& c : copying.slot) ctx_->finish(c);  // here, so that an error is reported
}

void Buffer::download(void* data, size_t bytes, size_t offset) const {
  if (bytes == 0) return;
  if (cached_) {
    copy_bytes(data, static_cast<const char*>(mapped_) + offset, bytes);
    return;
  }
  std::lock_guard<std::recursive_mutex> hold(ctx_->mutex());
  Buffer& staging = ctx_->staging(Memory::Download, bytes);
  const StagingSlots slots(staging.size(), bytes);
  const size_t pieces = (bytes + slots.size - 1) / slots.size;
  InFlight copying{*ctx_};
  auto fetch = [&](size_t k) {  // piece k into its slot
    copying.slot[k % slots.count] = ctx_->submit([&](VkCommandBuffer cb) {
      VkBufferCopy region{offset + k * slots.size, (k % slots.count) * slots.size, std::min(bytes - k * slots.size, slots.size)};
      vkCmdCopyBuffer(cb, buffer_, staging.handle(), 1, &region);
    });
  };
  fetch(0);
  for (size_t k = 0; k < pieces; ++k) {  // the next piece comes into the other slot while this one is copied out
    if (slots.count == 2 && k + 1 < pieces) fetch(k + 1);
    ctx_->finish(copying.slot[k % slots.count]);
    copy_bytes(static_cast<char*>(data) + k * slots.size,
               static_cast<const char*>(staging.mapped()) + (k % slots.count) * slots.size,
               std::min(bytes - k * slots.size, slots.size));
    if (slots.count == 1 && k + 1 < pieces) fetch(k + 1);
  }
  for (auto& c : copying.slot) ctx_->finish(c);  // here, so that an error is reported
}

}  // namespace repose::vk
