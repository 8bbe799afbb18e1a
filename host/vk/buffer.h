// One storage buffer in device memory (RAII, movable, non-copyable). Transfers go through a
// host-visible staging buffer, so the same code serves lavapipe (where all memory is host
// visible) and discrete GPUs (where device-local memory is not).
#pragma once
#include <cstddef>
#include <vulkan/vulkan.h>

namespace repose::vk {

class Context;

class Buffer {
 public:
  Buffer() = default;
  // usage is added to STORAGE | TRANSFER_SRC | TRANSFER_DST.
  Buffer(Context& ctx, size_t bytes, VkBufferUsageFlags extra_usage = 0, bool host_visible = false);
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  size_t size() const { return bytes_; }
  void* mapped() const { return mapped_; }  // non-null only for host-visible buffers

  // Copy bytes from/to host memory at `offset` (through staging unless host-visible).
  void upload(const void* data, size_t bytes, size_t offset = 0);
  void download(void* data, size_t bytes, size_t offset = 0) const;

 private:
  void release();
  Context* ctx_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  void* mapped_ = nullptr;
  size_t bytes_ = 0;
};

}  // namespace repose::vk
