// SPDX-License-Identifier: MIT
// calder::gpu internals: the Vulkan objects behind a Context, device
// buffers, compute kernels and one-shot command submission.
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "calder/gpu.hpp"

namespace calder::gpu {

// Throws calder::RunError naming the call unless result is VK_SUCCESS.
void check(VkResult result, const char* call);

// A storage buffer in device memory (host-visible where the device has no
// other kind, as lavapipe). Move-only; released with its context.
class Buffer {
 public:
  Buffer() = default;
  Buffer(Context::Impl& impl, std::size_t bytes);
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  [[nodiscard]] VkBuffer handle() const { return buffer_; }
  [[nodiscard]] std::size_t bytes() const { return bytes_; }

 private:
  void release();
  Context::Impl* impl_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  std::size_t bytes_ = 0;
};

// A compute pipeline of one SPIR-V module: `bindings` storage buffers
// (binding 0, 1, ...), push constants of `push_bytes`, and integer
// specialization constants 0, 1, ... (constant_id order).
class Kernel {
 public:
  Kernel() = default;
  Kernel(Context::Impl& impl, std::span<const std::uint32_t> spirv, std::uint32_t bindings,
         std::uint32_t push_bytes, std::span<const std::int32_t> constants);
  ~Kernel();
  Kernel(Kernel&& other) noexcept;
  Kernel& operator=(Kernel&& other) noexcept;
  Kernel(const Kernel&) = delete;
  Kernel& operator=(const Kernel&) = delete;

  // Points the kernel's storage buffers at these (bindings 0, 1, ...):
  // between submissions, not while one that uses the kernel is recorded.
  void bind(std::span<const Buffer* const> buffers);
  // Records a dispatch of `groups` workgroups (folded into x and y where
  // there are more than the device's x limit) with these push constants,
  // and a barrier after it.
  void record(VkCommandBuffer commands, const void* push, std::uint32_t groups);
  [[nodiscard]] bool valid() const { return pipeline_ != VK_NULL_HANDLE; }

 private:
  void release();
  Context::Impl* impl_ = nullptr;
  VkShaderModule module_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  std::uint32_t bindings_ = 0;
  std::uint32_t push_bytes_ = 0;
};

struct Context::Impl {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  std::uint32_t queue_family = 0;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  VkPhysicalDeviceMemoryProperties memory{};
  std::uint32_t max_groups_x = 65535;
  std::uint32_t max_storage_range = 0;
  DeviceInfo info;
  TransferStats stats;
  // A host-visible staging buffer, grown on demand.
  VkBuffer staging = VK_NULL_HANDLE;
  VkDeviceMemory staging_memory = VK_NULL_HANDLE;
  void* staging_map = nullptr;
  std::size_t staging_bytes = 0;

  ~Impl();
  // The index of a memory type allowed by `bits` with `flags`, or -1.
  [[nodiscard]] int memory_type(std::uint32_t bits, VkMemoryPropertyFlags flags) const;
  VkDeviceMemory allocate(VkMemoryRequirements needs, VkMemoryPropertyFlags preferred);
  // Records into the context's command buffer, submits it and waits.
  void submit(const std::function<void(VkCommandBuffer)>& record);
  // Copies host bytes into buffers / buffers back to host bytes, in one
  // submission each (through the staging buffer). Counted in stats.
  struct Upload {
    const Buffer* to;
    const void* from;
    std::size_t bytes;
  };
  struct Download {
    const Buffer* from;
    void* to;
    std::size_t bytes;
  };
  void upload(std::span<const Upload> copies);
  void download(std::span<const Download> copies);
  void ensure_staging(std::size_t bytes);
};

// A buffer of `count` elements of `T` (at least one, Vulkan has no empty buffer).
template <class T>
Buffer buffer_of(Context::Impl& impl, std::size_t count) {
  return Buffer(impl, (count > 0 ? count : 1) * sizeof(T));
}

}  // namespace calder::gpu
