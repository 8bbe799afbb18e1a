// One chosen Vulkan device, its compute queue, a command pool and staging buffers, on the
// process's Vulkan instance. With REPOSE_VALIDATION=1 in the environment the Khronos validation
// layer is enabled and every message it sends is counted and printed.
#pragma once
#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>
#include <vulkan/vulkan.h>

namespace repose::vk {

class Buffer;
class PipelineLibrary;
enum class Memory;

struct DeviceInfo {
  uint32_t index = 0;
  std::string name;
  std::string type;    // "cpu" (lavapipe), "discrete-gpu", ...
  std::string driver;  // driver name and info
  uint32_t api_version = 0;
  uint64_t device_local_bytes = 0;
  uint32_t max_storage_buffers = 0;
  uint64_t max_storage_range = 0;
  uint32_t max_groups[3] = {0, 0, 0};    // maxComputeWorkGroupCount
  uint64_t max_allocation = 0;           // maxMemoryAllocationSize
  uint32_t subgroup_size = 0;            // for the record: no kernel depends on it
  bool device_local_mappable = false;    // device buffers' memory type is host-mappable (no staging)
  bool float64 = false;                  // shaderFloat64 (the rounding correction needs it)
  bool rounds_like_ieee = false;         // / and sqrt correctly rounded (lavapipe: LLVM's own)
  bool denorm_preserve32 = false;        // shaderDenormPreserveFloat32 (vk/spirv_patch.h)
  std::string limits_text() const;       // one line for `repose devices` and error messages
};

// Transfers to and from device memory the host cannot map go through two host buffers (one each
// way) of at most this many bytes, in as many copies as a transfer needs: the host's share stays
// fixed however large the device's buffers (whole-buffer staging would take 2 x 16 GiB of pinned
// host memory at 1e8 spheres).
inline constexpr size_t kStagingBytes = size_t(64) << 20;

// The staging buffers' size: kStagingBytes, or REPOSE_STAGING=N (bytes, 1 ... kStagingBytes), which
// also sends every device buffer through them where the host could map it (lavapipe), so that CI
// runs a discrete GPU's transfers, in many small copies. Throws, naming the variable, if malformed.
size_t staging_bytes();
bool staging_forced();
// The size of a staging buffer made for a transfer of `bytes`: doubling from 1 MiB until it holds
// them, at most staging_bytes() (Context::staging; the memory a run needs counts two).
size_t staging_size_for(size_t bytes);

class Context {
 public:
  // The device `device_index` (< 0: the first discrete GPU, else the first device, which is
  // lavapipe on CPU machines), opened once per process and shared by every simulation that asks:
  // a calibration runs hundreds of simulations in one process, and a GPU driver (NVIDIA's, seen on
  // an H100 and an H200) refuses new instances after a few dozen have been created and destroyed.
  // The instance and devices live until the process ends. Thread-safe.
  static std::shared_ptr<Context> open(int device_index = -1);
  // Use open(); public for make_shared.
  Context(VkInstance instance, VkPhysicalDevice physical, const DeviceInfo& info, bool validation);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  // Every device the loader sees; does not create a logical device.
  static std::vector<DeviceInfo> list_devices();
  static int default_device_index(const std::vector<DeviceInfo>& devices);

  VkDevice device() const { return device_; }
  VkPhysicalDevice physical() const { return physical_; }
  VkQueue queue() const { return queue_; }
  VkCommandPool command_pool() const { return pool_; }
  const DeviceInfo& info() const { return info_; }
  // How the kernels round / and sqrt on this device (gpu::kRounding*): as the device does where it
  // rounds like IEEE, corrected elsewhere; REPOSE_ROUNDING=device|corrected|test overrides.
  uint32_t rounding() const { return rounding_; }
  // Memory type with all `required` flags, preferring `preferred`; throws if none.
  uint32_t memory_type(uint32_t type_bits, VkMemoryPropertyFlags required,
                       VkMemoryPropertyFlags preferred) const;
  VkMemoryPropertyFlags memory_flags(uint32_t type) const { return memory_.memoryTypes[type].propertyFlags; }
  // Messages from the validation layer so far in this process (0 when it is off).
  uint64_t validation_messages() const;
  bool validation_enabled() const;

  // Held while the queue, the command pool or the staging buffers are in use: simulations on
  // several threads share one context.
  std::recursive_mutex& mutex() { return mutex_; }
  // Records with `record`, submits, and waits.
  template <class F>
  void submit_and_wait(F&& record) {
    std::lock_guard<std::recursive_mutex> hold(mutex_);
    VkCommandBuffer cb = begin_commands();
    record(cb);
    end_and_submit(cb);
  }
  VkCommandBuffer begin_commands();
  void end_and_submit(VkCommandBuffer cb);
  // A submission the host goes on beside (a staging copy while the next piece is copied on the
  // host): submit() records and submits, finish() waits for it and frees it. Hold mutex() between.
  struct Submission {
    VkCommandBuffer commands = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
  };
  template <class F>
  Submission submit(F&& record) {
    VkCommandBuffer cb = begin_commands();
    record(cb);
    return submit_commands(cb);
  }
  void finish(Submission& s);
  // A host buffer for transfers one way (Memory::Upload or Memory::Download) of min(`bytes`,
  // staging_bytes()) or more, kept and grown up to staging_bytes(): a transfer allocates nothing.
  Buffer& staging(Memory direction, size_t bytes);
  // The device's compute pipelines (kernel_set.h), made on first call and kept with the device.
  PipelineLibrary& pipelines();

 private:
  void release();
  Submission submit_commands(VkCommandBuffer cb);
  VkInstance instance_ = VK_NULL_HANDLE;  // the process's, not owned
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  uint32_t queue_family_ = 0;
  DeviceInfo info_;
  bool validation_ = false;
  uint32_t rounding_ = 0;
  std::unique_ptr<Buffer> upload_staging_, download_staging_;
  std::unique_ptr<PipelineLibrary> pipelines_;
  VkPhysicalDeviceMemoryProperties memory_{};
  std::recursive_mutex mutex_;
};

}  // namespace repose::vk
