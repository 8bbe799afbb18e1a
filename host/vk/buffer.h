// One storage buffer in device memory (RAII, movable, non-copyable). Transfers go through the
// context's host-visible staging buffers, so the same code serves lavapipe (where all memory is
// host visible and cached) and discrete GPUs (where device-local memory is not host visible, or
// is but reads back uncached over the bus: a download then goes through cached host memory).
#pragma once
#include <cstddef>
#include <vulkan/vulkan.h>

namespace repose::vk {

class Context;

// Where a buffer lives: device-local memory, or host memory written by the host (Upload) or read
// by it (Download: cached where the device offers it).
enum class Memory { Device, Upload, Download };

class Buffer {
 public:
  Buffer() = default;
  // usage is added to STORAGE | TRANSFER_SRC | TRANSFER_DST.
  Buffer(Context& ctx, size_t bytes, VkBufferUsageFlags extra_usage = 0, Memory memory = Memory::Device);
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
  bool cached_ = false;  // mapped memory the host reads at full speed
  size_t bytes_ = 0;
};

}  // namespace repose::vk
