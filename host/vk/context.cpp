#include "vk/context.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "repose_shared.h"
#include "util/env_setting.h"
#include "vk/buffer.h"
#include "vk/kernel_set.h"
#include "vk/vk_check.h"

namespace repose::vk {

namespace {

bool validation_requested() {
  const char* v = std::getenv("REPOSE_VALIDATION");
  return v && std::strcmp(v, "0") != 0 && *v;
}

VkInstance create_instance(bool validation) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "repose";
  app.apiVersion = VK_API_VERSION_1_2;
  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ci.pApplicationInfo = &app;
  const char* layer = "VK_LAYER_KHRONOS_validation";
  const char* ext = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  if (validation) {
    ci.enabledLayerCount = 1;
    ci.ppEnabledLayerNames = &layer;
    ci.enabledExtensionCount = 1;
    ci.ppEnabledExtensionNames = &ext;
  }
  VkInstance instance = VK_NULL_HANDLE;
  VkResult r = vkCreateInstance(&ci, nullptr, &instance);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER)
    throw VulkanError("no Vulkan driver found (install mesa-vulkan-drivers for lavapipe)");
  if (r == VK_ERROR_LAYER_NOT_PRESENT)
    throw VulkanError("REPOSE_VALIDATION is set but VK_LAYER_KHRONOS_validation is not installed "
                      "(package vulkan-validationlayers)");
  VK_CHECK(r);
  return instance;
}

const char* type_name(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual-gpu";
    default: return "other";
  }
}

std::vector<VkPhysicalDevice> physical_devices(VkInstance instance) {
  uint32_t n = 0;
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &n, nullptr));
  std::vector<VkPhysicalDevice> devices(n);
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &n, devices.data()));
  return devices;
}

DeviceInfo describe(VkPhysicalDevice pd, uint32_t index) {
  VkPhysicalDeviceFloatControlsProperties float_controls{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FLOAT_CONTROLS_PROPERTIES};
  VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  subgroup.pNext = &float_controls;
  VkPhysicalDeviceMaintenance3Properties maintenance3{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
  maintenance3.pNext = &subgroup;
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  driver.pNext = &maintenance3;
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props.pNext = &driver;
  vkGetPhysicalDeviceProperties2(pd, &props);
  VkPhysicalDeviceMemoryProperties mem;
  vkGetPhysicalDeviceMemoryProperties(pd, &mem);
  DeviceInfo info;
  info.index = index;
  info.name = props.properties.deviceName;
  info.type = type_name(props.properties.deviceType);
  info.driver = std::string(driver.driverName) + " " + driver.driverInfo;
  info.api_version = props.properties.apiVersion;
  // The largest device-local heap (a GPU may list its small host-mappable window as a second one).
  for (uint32_t h = 0; h < mem.memoryHeapCount; ++h)
    if (mem.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
      info.device_local_bytes = std::max<uint64_t>(info.device_local_bytes, mem.memoryHeaps[h].size);
  info.max_storage_buffers = props.properties.limits.maxPerStageDescriptorStorageBuffers;
  info.max_storage_range = props.properties.limits.maxStorageBufferRange;
  VkPhysicalDeviceFeatures features;
  vkGetPhysicalDeviceFeatures(pd, &features);
  info.float64 = features.shaderFloat64 == VK_TRUE;
  info.rounds_like_ieee = driver.driverID == VK_DRIVER_ID_MESA_LLVMPIPE;
  info.denorm_preserve32 = float_controls.shaderDenormPreserveFloat32 == VK_TRUE;
  for (int k = 0; k < 3; ++k) info.max_groups[k] = props.properties.limits.maxComputeWorkGroupCount[k];
  info.max_allocation = maintenance3.maxMemoryAllocationSize;
  info.subgroup_size = subgroup.subgroupSize;
  // What vk::Buffer does: device buffers take the first device-local type, and are mapped when it
  // is host-visible and coherent (lavapipe's one type); a mappable type further down the list (a
  // GPU's resizable BAR) is not used.
  for (uint32_t t = 0; t < mem.memoryTypeCount; ++t) {
    VkMemoryPropertyFlags f = mem.memoryTypes[t].propertyFlags;
    if (!(f & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)) continue;
    info.device_local_mappable =
        (f & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) && (f & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    break;
  }
  return info;
}

// The process's Vulkan instance, with or without the validation layer: created on first use
// and kept until the process ends (never destroyed, see Context::open).
struct ProcessInstance {
  VkInstance handle = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  std::atomic<uint64_t> messages{0};
};

VkBool32 VKAPI_PTR count_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
                                 const VkDebugUtilsMessengerCallbackDataEXT* data, void* instance) {
  if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
    static_cast<ProcessInstance*>(instance)->messages++;
    std::fprintf(stderr, "vulkan validation: %s\n", data->pMessage);
  }
  return VK_FALSE;
}

std::mutex registry_mutex;

ProcessInstance& process_instance(bool validation) {
  static ProcessInstance* kept[2] = {nullptr, nullptr};
  std::lock_guard<std::mutex> hold(registry_mutex);
  ProcessInstance*& p = kept[validation ? 1 : 0];
  if (p) return *p;
  auto made = std::make_unique<ProcessInstance>();
  made->handle = create_instance(validation);
  if (validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(made->handle, "vkCreateDebugUtilsMessengerEXT"));
    if (!create) throw VulkanError("validation requested but VK_EXT_debug_utils is unavailable");
    VkDebugUtilsMessengerCreateInfoEXT mi{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    mi.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    mi.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    mi.pfnUserCallback = &count_message;
    mi.pUserData = made.get();
    VK_CHECK(create(made->handle, &mi, nullptr, &made->messenger));
  }
  p = made.release();
  return *p;
}

uint32_t choose_rounding(const DeviceInfo& d) {
  const char* v = std::getenv("REPOSE_ROUNDING");
  std::string asked = v ? v : "";
  uint32_t mode = d.rounds_like_ieee ? gpu::kRoundingDevice : gpu::kRoundingCorrected;
  if (asked == "device") mode = gpu::kRoundingDevice;
  else if (asked == "corrected") mode = gpu::kRoundingCorrected;
  else if (asked == "test") mode = gpu::kRoundingTest;
  else if (!asked.empty())
    throw VulkanError("REPOSE_ROUNDING = '" + asked + "': give device, corrected or test");
  if (mode != gpu::kRoundingDevice && !d.float64)
    throw VulkanError("'" + d.name + "' has no 64-bit floats, which the kernels need to round / and sqrt as the "
                      "cpu backend does; REPOSE_ROUNDING=device runs without (results then differ from the cpu "
                      "backend's in the last bits), or use --backend cpu");
  return mode;
}

}  // namespace

std::string DeviceInfo::limits_text() const {
  char line[384];
  std::snprintf(line, sizeof line,
                "workgroups %u x %u x %u, storage buffer range %.3g GiB, allocation %.3g GiB, %u storage buffers "
                "per stage, subgroup %u, device buffers %s, / and sqrt %s, denormals %s",
                max_groups[0], max_groups[1], max_groups[2], max_storage_range / 1073741824.0,
                max_allocation / 1073741824.0, max_storage_buffers, subgroup_size,
                device_local_mappable ? "mapped directly" : "reached through staging copies",
                rounds_like_ieee ? "rounded as IEEE" : float64 ? "corrected to IEEE in double precision"
                                                          : "not correctable (no 64-bit floats)",
                rounds_like_ieee || denorm_preserve32 ? "kept" : "maybe flushed to zero");
  return line;
}

std::vector<DeviceInfo> Context::list_devices() {
  VkInstance instance = process_instance(validation_requested()).handle;
  auto devices = physical_devices(instance);
  std::vector<DeviceInfo> out;
  for (uint32_t i = 0; i < devices.size(); ++i) out.push_back(describe(devices[i], i));
  return out;
}

int Context::default_device_index(const std::vector<DeviceInfo>& devices) {
  for (const char* type : {"discrete-gpu", "integrated-gpu", "virtual-gpu"})
    for (const auto& d : devices)
      if (d.type == type) return static_cast<int>(d.index);
  return devices.empty() ? -1 : 0;
}

std::shared_ptr<Context> Context::open(int device_index) {
  bool validation = validation_requested();
  VkInstance instance = process_instance(validation).handle;
  auto devices = physical_devices(instance);
  if (devices.empty()) throw VulkanError("no Vulkan device found (install mesa-vulkan-drivers for lavapipe)");
  std::vector<DeviceInfo> infos;
  for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describe(devices[i], i));
  if (device_index < 0) device_index = default_device_index(infos);
  if (device_index >= static_cast<int>(devices.size()))
    throw VulkanError("--device " + std::to_string(device_index) + ": only " + std::to_string(devices.size()) +
                      " Vulkan device(s); see `repose devices`");
  static auto* opened = new std::map<std::pair<bool, int>, std::shared_ptr<Context>>();
  std::lock_guard<std::mutex> hold(registry_mutex);
  auto& slot = (*opened)[{validation, device_index}];
  if (!slot) slot = std::make_shared<Context>(instance, devices[device_index], infos[device_index], validation);
  return slot;
}

uint64_t Context::validation_messages() const { return validation_ ? process_instance(true).messages.load() : 0; }
bool Context::validation_enabled() const { return validation_ && process_instance(true).messenger != VK_NULL_HANDLE; }

Context::Context(VkInstance instance, VkPhysicalDevice physical, const DeviceInfo& info, bool validation)
    : instance_(instance), physical_(physical), info_(info), validation_(validation) {
  try {
    vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);

    uint32_t nq = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &nq, nullptr);
    std::vector<VkQueueFamilyProperties> families(nq);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &nq, families.data());
    bool found = false;
    for (uint32_t q = 0; q < nq && !found; ++q)
      if (families[q].queueFlags & VK_QUEUE_COMPUTE_BIT) { queue_family_ = q; found = true; }
    if (!found) throw VulkanError("device '" + info_.name + "' has no compute queue");

    float priority = 1.0f;
    VkDeviceQueueCreateInfo qi{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qi.queueFamilyIndex = queue_family_;
    qi.queueCount = 1;
    qi.pQueuePriorities = &priority;
    rounding_ = choose_rounding(info_);
    staging_bytes();  // a malformed REPOSE_STAGING is refused here, before anything is allocated
    VkPhysicalDeviceFeatures enabled{};
    enabled.shaderFloat64 = info_.float64 ? VK_TRUE : VK_FALSE;
    VkDeviceCreateInfo di{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    di.pEnabledFeatures = &enabled;
    di.queueCreateInfoCount = 1;
    di.pQueueCreateInfos = &qi;
    VK_CHECK(vkCreateDevice(physical_, &di, nullptr, &device_));
    vkGetDeviceQueue(device_, queue_family_, 0, &queue_);

    VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pi.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pi.queueFamilyIndex = queue_family_;
    VK_CHECK(vkCreateCommandPool(device_, &pi, nullptr, &pool_));
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(vkCreateFence(device_, &fi, nullptr, &fence_));
  } catch (...) {
    release();
    throw;
  }
}

Context::~Context() { release(); }

void Context::release() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    pipelines_.reset();
    upload_staging_.reset();
    download_staging_.reset();
    if (fence_) vkDestroyFence(device_, fence_, nullptr);
    if (pool_) vkDestroyCommandPool(device_, pool_, nullptr);
    vkDestroyDevice(device_, nullptr);
    device_ = VK_NULL_HANDLE;
  }
}

uint32_t Context::memory_type(uint32_t type_bits, VkMemoryPropertyFlags required,
                              VkMemoryPropertyFlags preferred) const {
  for (int pass = 0; pass < 2; ++pass) {
    VkMemoryPropertyFlags want = pass == 0 ? (required | preferred) : required;
    for (uint32_t t = 0; t < memory_.memoryTypeCount; ++t)
      if ((type_bits & (1u << t)) && (memory_.memoryTypes[t].propertyFlags & want) == want) return t;
  }
  throw VulkanError("no Vulkan memory type with the required properties");
}

size_t staging_bytes() {
  static const size_t bytes = env_whole_number("REPOSE_STAGING", kStagingBytes, kStagingBytes);
  return bytes;
}

bool staging_forced() {
  static const bool forced = [] {
    const char* text = std::getenv("REPOSE_STAGING");
    return text && *text;
  }();
  return forced;
}

size_t staging_size_for(size_t bytes) {
  size_t most = staging_bytes(), size = std::min(size_t(1) << 20, most);
  while (size < bytes && size < most) size = std::min(2 * size, most);
  return size;
}

Buffer& Context::staging(Memory direction, size_t bytes) {
  std::unique_ptr<Buffer>& kept = direction == Memory::Upload ? upload_staging_ : download_staging_;
  if (!kept || kept->size() < std::min(bytes, staging_bytes())) {
    kept.reset();  // free the smaller one first
    kept = std::make_unique<Buffer>(*this, staging_size_for(bytes), 0, direction);
  }
  return *kept;
}

PipelineLibrary& Context::pipelines() {
  std::lock_guard<std::recursive_mutex> hold(mutex_);
  if (!pipelines_) pipelines_ = std::make_unique<PipelineLibrary>(*this);
  return *pipelines_;
}

VkCommandBuffer Context::begin_commands() {
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = pool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cb;
  VK_CHECK(vkAllocateCommandBuffers(device_, &ai, &cb));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cb, &bi));
  return cb;
}

Context::Submission Context::submit_commands(VkCommandBuffer cb) {
  VK_CHECK(vkEndCommandBuffer(cb));
  Submission s{cb, VK_NULL_HANDLE};
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VK_CHECK(vkCreateFence(device_, &fi, nullptr, &s.fence));
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cb;
  VK_CHECK(vkQueueSubmit(queue_, 1, &si, s.fence));
  return s;
}

void Context::finish(Submission& s) {
  if (s.fence == VK_NULL_HANDLE) return;
  VK_CHECK(vkWaitForFences(device_, 1, &s.fence, VK_TRUE, UINT64_MAX));
  vkDestroyFence(device_, s.fence, nullptr);
  vkFreeCommandBuffers(device_, pool_, 1, &s.commands);
  s = Submission{};
}

void Context::end_and_submit(VkCommandBuffer cb) {
  VK_CHECK(vkEndCommandBuffer(cb));
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cb;
  VK_CHECK(vkResetFences(device_, 1, &fence_));
  VK_CHECK(vkQueueSubmit(queue_, 1, &si, fence_));
  VK_CHECK(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX));
  vkFreeCommandBuffers(device_, pool_, 1, &cb);
}

}  // namespace repose::vk
