// SPDX-License-Identifier: MIT
// calder::gpu: the Vulkan instance, device, queue, buffers and kernels.
#include "context.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>

#include "calder/error.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define CALDER_GPU_LEAK_CHECKS 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(leak_sanitizer)
#define CALDER_GPU_LEAK_CHECKS 1
#endif
#endif
#if defined(CALDER_GPU_LEAK_CHECKS)
#include <sanitizer/lsan_interface.h>
#endif

namespace calder::gpu {

namespace {

// What a Vulkan driver allocates while the loader asks it for its devices,
// not counted as leaks by a leak-checking build. A driver may keep blocks
// from a one-time set-up for as long as it is loaded, and the loader unloads
// it with the last instance, which loses them (Mesa's llvmpipe on an AMD
// EPYC: two blocks of 128 bytes, reported from an unloaded library). They
// are the driver's, not calder's.
class DriverAllocations {
 public:
  DriverAllocations() {
#if defined(CALDER_GPU_LEAK_CHECKS)
    __lsan_disable();
#endif
  }
  ~DriverAllocations() {
#if defined(CALDER_GPU_LEAK_CHECKS)
    __lsan_enable();
#endif
  }
  DriverAllocations(const DriverAllocations&) = delete;
  DriverAllocations& operator=(const DriverAllocations&) = delete;
};

std::string version_text(std::uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
         "." + std::to_string(VK_API_VERSION_PATCH(v));
}

const char* type_text(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return "CPU";
    default:
      return "other";
  }
}

// The first queue family with compute, or -1.
int compute_family(VkPhysicalDevice device) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  for (std::uint32_t i = 0; i < count; ++i) {
    if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) != 0) return static_cast<int>(i);
  }
  return -1;
}

DeviceInfo describe(VkPhysicalDevice device, int index) {
  VkPhysicalDeviceDriverProperties driver{};
  driver.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES;
  VkPhysicalDeviceProperties2 properties{};
  properties.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
  VkPhysicalDeviceProperties plain{};
  vkGetPhysicalDeviceProperties(device, &plain);
  const bool has_driver = plain.apiVersion >= VK_API_VERSION_1_2;
  if (has_driver) {
    properties.pNext = &driver;
    vkGetPhysicalDeviceProperties2(device, &properties);
  }
  VkPhysicalDeviceFeatures features{};
  vkGetPhysicalDeviceFeatures(device, &features);
  VkPhysicalDeviceMemoryProperties memory{};
  vkGetPhysicalDeviceMemoryProperties(device, &memory);
  DeviceInfo info;
  info.index = index;
  info.name = plain.deviceName;
  info.type = type_text(plain.deviceType);
  info.api_version = version_text(plain.apiVersion);
  if (has_driver) info.driver = std::string(driver.driverName) + " " + driver.driverInfo;
  info.vendor_id = plain.vendorID;
  info.device_id = plain.deviceID;
  info.compute = compute_family(device) >= 0;
  info.float64 = features.shaderFloat64 == VK_TRUE;
  info.max_buffer_bytes = plain.limits.maxStorageBufferRange;
  for (std::uint32_t h = 0; h < memory.memoryHeapCount; ++h) {
    if ((memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) != 0) {
      info.memory_bytes = std::max<std::uint64_t>(info.memory_bytes, memory.memoryHeaps[h].size);
    }
  }
  return info;
}

VkInstance make_instance(std::string* why) {
  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "calder";
  app.pEngineName = "calder";
  app.apiVersion = VK_API_VERSION_1_1;
  VkInstanceCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  create.pApplicationInfo = &app;
  VkInstance instance = VK_NULL_HANDLE;
  const VkResult result = vkCreateInstance(&create, nullptr, &instance);
  if (result != VK_SUCCESS) {
    if (why != nullptr) {
      *why = result == VK_ERROR_INCOMPATIBLE_DRIVER
                 ? "Vulkan has no driver (install mesa-vulkan-drivers or a GPU's driver)"
                 : "vkCreateInstance failed (VkResult " + std::to_string(result) + ")";
    }
    return VK_NULL_HANDLE;
  }
  return instance;
}

std::vector<VkPhysicalDevice> physical_devices(VkInstance instance) {
  const DriverAllocations drivers;
  std::uint32_t count = 0;
  check(vkEnumeratePhysicalDevices(instance, &count, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> out(count);
  check(vkEnumeratePhysicalDevices(instance, &count, out.data()), "vkEnumeratePhysicalDevices");
  out.resize(count);
  return out;
}

// The device a Context(-1) takes: kDeviceVariable's index, else the first
// with compute; -1 if none.
int chosen_device(const std::vector<DeviceInfo>& found) {
  if (const char* text = std::getenv(kDeviceVariable); text != nullptr && *text != '\0') {
    // Digits only, and few enough to be an index: no sign, no spaces, no
    // value that wraps to another device (4294967296 is not device 0).
    const std::string digits(text);
    const bool valid =
        digits.size() <= 6 && digits.find_first_not_of("0123456789") == std::string::npos;
    if (!valid) {
      throw InvalidArgument(std::string("calder::gpu: ") + kDeviceVariable +
                            " must be a device index, 0 to 999999 (got '" +
                            detail::printable(digits) + "')");
    }
    return std::stoi(digits);
  }
  for (const DeviceInfo& d : found) {
    if (d.compute) return d.index;
  }
  return -1;
}

}  // namespace

void check(VkResult result, const char* call) {
  if (result != VK_SUCCESS) {
    throw RunError(std::string("calder::gpu: ") + call + " failed (VkResult " +
                   std::to_string(result) + ")");
  }
}

std::vector<DeviceInfo> devices(std::string* why_none) {
  VkInstance instance = make_instance(why_none);
  if (instance == VK_NULL_HANDLE) return {};
  std::vector<DeviceInfo> out;
  try {
    const std::vector<VkPhysicalDevice> found = physical_devices(instance);
    for (std::size_t i = 0; i < found.size(); ++i) {
      out.push_back(describe(found[i], static_cast<int>(i)));
    }
  } catch (...) {
    vkDestroyInstance(instance, nullptr);
    throw;
  }
  vkDestroyInstance(instance, nullptr);
  if (out.empty() && why_none != nullptr) *why_none = "Vulkan sees no device";
  return out;
}

// --- the context ---

namespace {

void open_device(Context::Impl& c, int requested) {
  std::string why;
  c.instance = make_instance(&why);
  if (c.instance == VK_NULL_HANDLE) throw InvalidArgument("calder::gpu: no Vulkan device: " + why);
  const std::vector<VkPhysicalDevice> found = physical_devices(c.instance);
  std::vector<DeviceInfo> infos;
  for (std::size_t i = 0; i < found.size(); ++i) {
    infos.push_back(describe(found[i], static_cast<int>(i)));
  }
  const int index = requested >= 0 ? requested : chosen_device(infos);
  if (found.empty()) throw InvalidArgument("calder::gpu: no Vulkan device: Vulkan sees none");
  if (index < 0) throw InvalidArgument("calder::gpu: no Vulkan device with compute");
  if (static_cast<std::size_t>(index) >= found.size()) {
    throw InvalidArgument("calder::gpu: no Vulkan device " + std::to_string(index) +
                          " (Vulkan sees " + std::to_string(found.size()) + ")");
  }
  c.info = infos[static_cast<std::size_t>(index)];
  if (!c.info.compute) {
    throw InvalidArgument("calder::gpu: device " + std::to_string(index) + " (" + c.info.name +
                          ") has no compute queue");
  }
  c.physical = found[static_cast<std::size_t>(index)];
  c.queue_family = static_cast<std::uint32_t>(compute_family(c.physical));
  vkGetPhysicalDeviceMemoryProperties(c.physical, &c.memory);
  VkPhysicalDeviceProperties properties{};
  vkGetPhysicalDeviceProperties(c.physical, &properties);
  c.max_groups_x = properties.limits.maxComputeWorkGroupCount[0];
  c.max_storage_range = properties.limits.maxStorageBufferRange;
}

void create_device(Context::Impl& c) {
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue{};
  queue.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  queue.queueFamilyIndex = c.queue_family;
  queue.queueCount = 1;
  queue.pQueuePriorities = &priority;
  VkPhysicalDeviceFeatures features{};
  features.shaderFloat64 = c.info.float64 ? VK_TRUE : VK_FALSE;
  VkDeviceCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  create.queueCreateInfoCount = 1;
  create.pQueueCreateInfos = &queue;
  create.pEnabledFeatures = &features;
  check(vkCreateDevice(c.physical, &create, nullptr, &c.device), "vkCreateDevice");
  vkGetDeviceQueue(c.device, c.queue_family, 0, &c.queue);
  VkCommandPoolCreateInfo pool{};
  pool.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool.queueFamilyIndex = c.queue_family;
  check(vkCreateCommandPool(c.device, &pool, nullptr, &c.pool), "vkCreateCommandPool");
  VkCommandBufferAllocateInfo allocate{};
  allocate.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  allocate.commandPool = c.pool;
  allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocate.commandBufferCount = 1;
  check(vkAllocateCommandBuffers(c.device, &allocate, &c.commands), "vkAllocateCommandBuffers");
  VkFenceCreateInfo fence{};
  fence.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  check(vkCreateFence(c.device, &fence, nullptr, &c.fence), "vkCreateFence");
}

}  // namespace

Context::Impl::~Impl() {
  if (device != VK_NULL_HANDLE) {
    vkDeviceWaitIdle(device);
    if (staging != VK_NULL_HANDLE) vkDestroyBuffer(device, staging, nullptr);
    if (staging_memory != VK_NULL_HANDLE) vkFreeMemory(device, staging_memory, nullptr);
    if (fence != VK_NULL_HANDLE) vkDestroyFence(device, fence, nullptr);
    if (pool != VK_NULL_HANDLE) vkDestroyCommandPool(device, pool, nullptr);
    vkDestroyDevice(device, nullptr);
  }
  if (instance != VK_NULL_HANDLE) vkDestroyInstance(instance, nullptr);
}

int Context::Impl::memory_type(std::uint32_t bits, VkMemoryPropertyFlags flags) const {
  for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
    if ((bits & (1u << i)) != 0 && (memory.memoryTypes[i].propertyFlags & flags) == flags) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

VkDeviceMemory Context::Impl::allocate(VkMemoryRequirements needs,
                                       VkMemoryPropertyFlags preferred) {
  int type = memory_type(needs.memoryTypeBits, preferred);
  if (type < 0) type = memory_type(needs.memoryTypeBits, 0);
  if (type < 0) throw RunError("calder::gpu: no memory type for a buffer");
  VkMemoryAllocateInfo allocate{};
  allocate.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  allocate.allocationSize = needs.size;
  allocate.memoryTypeIndex = static_cast<std::uint32_t>(type);
  VkDeviceMemory out = VK_NULL_HANDLE;
  const VkResult result = vkAllocateMemory(device, &allocate, nullptr, &out);
  if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY) {
    throw RunError("calder::gpu: out of device memory (" + std::to_string(needs.size) +
                   " bytes asked for, device " + info.name + ")");
  }
  check(result, "vkAllocateMemory");
  return out;
}

void Context::Impl::submit(const std::function<void(VkCommandBuffer)>& record) {
  check(vkResetCommandBuffer(commands, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(commands, &begin), "vkBeginCommandBuffer");
  // The earlier submissions' writes before this one's accesses, and this
  // one's writes before the host reads them.
  VkMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  barrier.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                       VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
  record(commands);
  barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0,
                       1, &barrier, 0, nullptr, 0, nullptr);
  check(vkEndCommandBuffer(commands), "vkEndCommandBuffer");
  VkSubmitInfo submit_info{};
  submit_info.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit_info.commandBufferCount = 1;
  submit_info.pCommandBuffers = &commands;
  check(vkResetFences(device, 1, &fence), "vkResetFences");
  check(vkQueueSubmit(queue, 1, &submit_info, fence), "vkQueueSubmit");
  check(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  ++stats.submits;
}

void Context::Impl::ensure_staging(std::size_t bytes) {
  if (bytes <= staging_bytes) return;
  if (staging != VK_NULL_HANDLE) {
    vkDestroyBuffer(device, staging, nullptr);
    vkFreeMemory(device, staging_memory, nullptr);
    staging = VK_NULL_HANDLE;
    staging_memory = VK_NULL_HANDLE;
    staging_bytes = 0;
  }
  VkBufferCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  create.size = bytes;
  create.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  create.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  check(vkCreateBuffer(device, &create, nullptr, &staging), "vkCreateBuffer");
  VkMemoryRequirements needs{};
  vkGetBufferMemoryRequirements(device, staging, &needs);
  const VkMemoryPropertyFlags host =
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  if (memory_type(needs.memoryTypeBits, host) < 0) {
    throw RunError("calder::gpu: the device has no host-visible coherent memory");
  }
  staging_memory = allocate(needs, host);
  check(vkBindBufferMemory(device, staging, staging_memory, 0), "vkBindBufferMemory");
  check(vkMapMemory(device, staging_memory, 0, VK_WHOLE_SIZE, 0, &staging_map), "vkMapMemory");
  staging_bytes = bytes;
}

void Context::Impl::upload(std::span<const Upload> copies) {
  std::size_t total = 0;
  for (const Upload& u : copies) total += u.bytes;
  if (total == 0) return;
  ensure_staging(total);
  std::size_t offset = 0;
  for (const Upload& u : copies) {
    if (u.bytes == 0) continue;  // an empty array's pointer may be null
    std::memcpy(static_cast<char*>(staging_map) + offset, u.from, u.bytes);
    offset += u.bytes;
  }
  submit([&](VkCommandBuffer cb) {
    std::size_t at = 0;
    for (const Upload& u : copies) {
      if (u.bytes == 0) continue;
      const VkBufferCopy region{at, 0, u.bytes};
      vkCmdCopyBuffer(cb, staging, u.to->handle(), 1, &region);
      at += u.bytes;
    }
  });
  stats.uploads += copies.size();
  stats.upload_bytes += total;
}

void Context::Impl::download(std::span<const Download> copies) {
  std::size_t total = 0;
  for (const Download& d : copies) total += d.bytes;
  if (total == 0) return;
  ensure_staging(total);
  submit([&](VkCommandBuffer cb) {
    std::size_t at = 0;
    for (const Download& d : copies) {
      if (d.bytes == 0) continue;
      const VkBufferCopy region{0, at, d.bytes};
      vkCmdCopyBuffer(cb, d.from->handle(), staging, 1, &region);
      at += d.bytes;
    }
  });
  std::size_t offset = 0;
  for (const Download& d : copies) {
    if (d.bytes == 0) continue;
    std::memcpy(d.to, static_cast<const char*>(staging_map) + offset, d.bytes);
    offset += d.bytes;
  }
  stats.downloads += copies.size();
  stats.download_bytes += total;
}

Context::Context(int device) : impl_(std::make_unique<Impl>()) {
  open_device(*impl_, device);
  if (!impl_->info.compute) throw InvalidArgument("calder::gpu: the device has no compute queue");
  create_device(*impl_);
}

Context::~Context() = default;
Context::Context(Context&&) noexcept = default;
Context& Context::operator=(Context&&) noexcept = default;

const DeviceInfo& Context::info() const { return impl_->info; }
const TransferStats& Context::stats() const { return impl_->stats; }
void Context::reset_stats() { impl_->stats = {}; }

// --- buffers ---

Buffer::Buffer(Context::Impl& impl, std::size_t bytes) : impl_(&impl), bytes_(bytes) {
  if (impl.max_storage_range != 0 && bytes > impl.max_storage_range) {
    throw RunError("calder::gpu: a buffer of " + std::to_string(bytes) +
                   " bytes exceeds the device's storage buffer range (" +
                   std::to_string(impl.max_storage_range) + " bytes, device " + impl.info.name +
                   ")");
  }
  VkBufferCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  create.size = bytes;
  create.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                 VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  create.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  check(vkCreateBuffer(impl.device, &create, nullptr, &buffer_), "vkCreateBuffer");
  VkMemoryRequirements needs{};
  vkGetBufferMemoryRequirements(impl.device, buffer_, &needs);
  try {
    memory_ = impl.allocate(needs, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  } catch (...) {
    vkDestroyBuffer(impl.device, buffer_, nullptr);
    throw;
  }
  check(vkBindBufferMemory(impl.device, buffer_, memory_, 0), "vkBindBufferMemory");
}

void Buffer::release() {
  if (impl_ == nullptr) return;
  if (buffer_ != VK_NULL_HANDLE) vkDestroyBuffer(impl_->device, buffer_, nullptr);
  if (memory_ != VK_NULL_HANDLE) vkFreeMemory(impl_->device, memory_, nullptr);
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
}

Buffer::~Buffer() { release(); }
Buffer::Buffer(Buffer&& other) noexcept
    : impl_(std::exchange(other.impl_, nullptr)),
      buffer_(std::exchange(other.buffer_, VK_NULL_HANDLE)),
      memory_(std::exchange(other.memory_, VK_NULL_HANDLE)),
      bytes_(std::exchange(other.bytes_, 0)) {}
Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    release();
    impl_ = std::exchange(other.impl_, nullptr);
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    bytes_ = std::exchange(other.bytes_, 0);
  }
  return *this;
}

// --- kernels ---

namespace {

VkDescriptorSetLayout make_set_layout(VkDevice device, std::uint32_t bindings) {
  std::vector<VkDescriptorSetLayoutBinding> rows(bindings);
  for (std::uint32_t i = 0; i < bindings; ++i) {
    rows[i].binding = i;
    rows[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    rows[i].descriptorCount = 1;
    rows[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  }
  VkDescriptorSetLayoutCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  create.bindingCount = bindings;
  create.pBindings = rows.data();
  VkDescriptorSetLayout out = VK_NULL_HANDLE;
  check(vkCreateDescriptorSetLayout(device, &create, nullptr, &out), "vkCreateDescriptorSetLayout");
  return out;
}

VkPipeline make_pipeline(VkDevice device, VkShaderModule module, VkPipelineLayout layout,
                         std::span<const std::int32_t> constants) {
  std::vector<VkSpecializationMapEntry> entries(constants.size());
  for (std::size_t i = 0; i < constants.size(); ++i) {
    entries[i].constantID = static_cast<std::uint32_t>(i);
    entries[i].offset = static_cast<std::uint32_t>(i * sizeof(std::int32_t));
    entries[i].size = sizeof(std::int32_t);
  }
  VkSpecializationInfo specialization{};
  specialization.mapEntryCount = static_cast<std::uint32_t>(entries.size());
  specialization.pMapEntries = entries.data();
  specialization.dataSize = constants.size() * sizeof(std::int32_t);
  specialization.pData = constants.data();
  VkComputePipelineCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  create.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  create.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  create.stage.module = module;
  create.stage.pName = "main";
  create.stage.pSpecializationInfo = constants.empty() ? nullptr : &specialization;
  create.layout = layout;
  VkPipeline out = VK_NULL_HANDLE;
  check(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &create, nullptr, &out),
        "vkCreateComputePipelines");
  return out;
}

}  // namespace

Kernel::Kernel(Context::Impl& impl, std::span<const std::uint32_t> spirv, std::uint32_t bindings,
               std::uint32_t push_bytes, std::span<const std::int32_t> constants)
    : impl_(&impl), bindings_(bindings), push_bytes_(push_bytes) {
  VkDevice device = impl.device;
  try {
    VkShaderModuleCreateInfo module{};
    module.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    module.codeSize = spirv.size_bytes();
    module.pCode = spirv.data();
    check(vkCreateShaderModule(device, &module, nullptr, &module_), "vkCreateShaderModule");
    set_layout_ = make_set_layout(device, bindings);
    VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes};
    VkPipelineLayoutCreateInfo layout{};
    layout.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    layout.setLayoutCount = 1;
    layout.pSetLayouts = &set_layout_;
    layout.pushConstantRangeCount = push_bytes > 0 ? 1 : 0;
    layout.pPushConstantRanges = &push;
    check(vkCreatePipelineLayout(device, &layout, nullptr, &layout_), "vkCreatePipelineLayout");
    pipeline_ = make_pipeline(device, module_, layout_, constants);
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, bindings};
    VkDescriptorPoolCreateInfo pool{};
    pool.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pool.maxSets = 1;
    pool.poolSizeCount = 1;
    pool.pPoolSizes = &size;
    check(vkCreateDescriptorPool(device, &pool, nullptr, &pool_), "vkCreateDescriptorPool");
    VkDescriptorSetAllocateInfo allocate{};
    allocate.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    allocate.descriptorPool = pool_;
    allocate.descriptorSetCount = 1;
    allocate.pSetLayouts = &set_layout_;
    check(vkAllocateDescriptorSets(device, &allocate, &set_), "vkAllocateDescriptorSets");
  } catch (...) {
    release();
    throw;
  }
}

void Kernel::release() {
  if (impl_ == nullptr) return;
  VkDevice device = impl_->device;
  if (pool_ != VK_NULL_HANDLE) vkDestroyDescriptorPool(device, pool_, nullptr);
  if (pipeline_ != VK_NULL_HANDLE) vkDestroyPipeline(device, pipeline_, nullptr);
  if (layout_ != VK_NULL_HANDLE) vkDestroyPipelineLayout(device, layout_, nullptr);
  if (set_layout_ != VK_NULL_HANDLE) vkDestroyDescriptorSetLayout(device, set_layout_, nullptr);
  if (module_ != VK_NULL_HANDLE) vkDestroyShaderModule(device, module_, nullptr);
  pool_ = VK_NULL_HANDLE;
  pipeline_ = VK_NULL_HANDLE;
  layout_ = VK_NULL_HANDLE;
  set_layout_ = VK_NULL_HANDLE;
  module_ = VK_NULL_HANDLE;
  set_ = VK_NULL_HANDLE;
}

Kernel::~Kernel() { release(); }
Kernel::Kernel(Kernel&& other) noexcept
    : impl_(std::exchange(other.impl_, nullptr)),
      module_(std::exchange(other.module_, VK_NULL_HANDLE)),
      set_layout_(std::exchange(other.set_layout_, VK_NULL_HANDLE)),
      layout_(std::exchange(other.layout_, VK_NULL_HANDLE)),
      pipeline_(std::exchange(other.pipeline_, VK_NULL_HANDLE)),
      pool_(std::exchange(other.pool_, VK_NULL_HANDLE)),
      set_(std::exchange(other.set_, VK_NULL_HANDLE)),
      bindings_(other.bindings_),
      push_bytes_(other.push_bytes_) {}
Kernel& Kernel::operator=(Kernel&& other) noexcept {
  if (this != &other) {
    release();
    impl_ = std::exchange(other.impl_, nullptr);
    module_ = std::exchange(other.module_, VK_NULL_HANDLE);
    set_layout_ = std::exchange(other.set_layout_, VK_NULL_HANDLE);
    layout_ = std::exchange(other.layout_, VK_NULL_HANDLE);
    pipeline_ = std::exchange(other.pipeline_, VK_NULL_HANDLE);
    pool_ = std::exchange(other.pool_, VK_NULL_HANDLE);
    set_ = std::exchange(other.set_, VK_NULL_HANDLE);
    bindings_ = other.bindings_;
    push_bytes_ = other.push_bytes_;
  }
  return *this;
}

void Kernel::bind(std::span<const Buffer* const> buffers) {
  std::vector<VkDescriptorBufferInfo> infos(buffers.size());
  std::vector<VkWriteDescriptorSet> writes(buffers.size());
  for (std::size_t i = 0; i < buffers.size(); ++i) {
    infos[i] = {buffers[i]->handle(), 0, VK_WHOLE_SIZE};
    writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[i].dstSet = set_;
    writes[i].dstBinding = static_cast<std::uint32_t>(i);
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(impl_->device, static_cast<std::uint32_t>(writes.size()), writes.data(), 0,
                         nullptr);
}

void Kernel::record(VkCommandBuffer commands, const void* push, std::uint32_t groups) {
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0,
                          nullptr);
  if (push_bytes_ > 0) {
    vkCmdPushConstants(commands, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes_, push);
  }
  const std::uint32_t x = std::min(groups, impl_->max_groups_x);
  const std::uint32_t y = (groups + x - 1) / x;
  vkCmdDispatch(commands, x, y, 1);
  VkMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask =
      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1,
                       &barrier, 0, nullptr, 0, nullptr);
  ++impl_->stats.dispatches;
}

}  // namespace calder::gpu
