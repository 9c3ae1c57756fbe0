// The hand-written baseline: the scene's command stream recorded with raw
// Vulkan calls, the way a competent D3D11-style renderer on Vulkan 1.3 would:
// pipelines pre-built (2 blend variants x 2 shader pairs) with the same dynamic
// state the RHI declares, one dynamic-rendering pass per batch, push
// descriptors for the constant buffer, vkCmdBindVertexBuffers2 with a dynamic
// stride. Its own VkInstance/VkDevice on the physical device the RHI picks.
#pragma once

#include <vulkan/vulkan.h>

#include <array>
#include <string>

#include "bench_scene.h"

namespace bench {

class RawVulkan {
 public:
  // Exits with a message when no suitable device exists.
  explicit RawVulkan(const SceneShaders& shaders);
  ~RawVulkan();
  RawVulkan(const RawVulkan&) = delete;
  RawVulkan& operator=(const RawVulkan&) = delete;

  const std::string& DeviceName() const { return deviceName_; }

  // The timed part: begins the command buffer (its pool was reset after the
  // previous batch's fence), one
  // barrier, begins rendering, then `draws` draws of the scene stream.
  // reemitDynamicState: also re-set viewport/scissor/topology/primitive
  // restart after every pipeline bind (what the RHI does today) - a diagnostic.
  void RecordBatch(int draws, bool reemitDynamicState);
  // The untimed part: ends rendering and the command buffer, submits, waits,
  // resets the command pool.
  void SubmitAndWait();
  // One untimed batch (not through RecordBatch, so profiles of RecordBatch
  // see only timed batches).
  void Warmup();

 private:
  void CreateDevice();
  void CreateResources();
  void CreatePipelines(const SceneShaders& shaders);
  VkBuffer CreateHostBuffer(VkBufferUsageFlags usage, const void* data, VkDeviceSize size, VkDeviceMemory* memory);
  uint32_t FindMemoryType(uint32_t typeBits, VkMemoryPropertyFlags flags) const;
  void SetPassState(VkCommandBuffer commands);
  // Ends, submits and waits for the command buffer, then resets its pool.
  void EndSubmitAndWait();
  void Record(int draws, bool reemitDynamicState);

  VkInstance instance_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  std::string deviceName_;
  VkPhysicalDeviceMemoryProperties memory_{};
  PFN_vkCmdPushDescriptorSetKHR vkCmdPushDescriptorSetKHR_ = nullptr;

  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer commands_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;

  VkImage target_ = VK_NULL_HANDLE;
  VkDeviceMemory targetMemory_ = VK_NULL_HANDLE;
  VkImageView targetView_ = VK_NULL_HANDLE;
  std::array<VkBuffer, 2> vertexBuffers_{};
  std::array<VkBuffer, 2> constantBuffers_{};
  std::array<VkDeviceMemory, 4> bufferMemory_{};

  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  std::array<VkPipeline, 4> pipelines_{};  // [pair * 2 + blend]
};

}  // namespace bench
