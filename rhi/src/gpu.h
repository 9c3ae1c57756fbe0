// The Vulkan core every backend object shares: instance, device, queue,
// memory types, command submission with serials, and deferred destruction.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <deque>
#include <functional>
#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "rhi/rhi.h"

namespace rhi::vk {

// What the chosen device can do beyond Vulkan 1.3 core, decided once at creation.
struct GpuCapabilities {
  bool transformFeedback = false;   // VK_EXT_transform_feedback
  bool transformFeedbackQueries = false;
  bool transformFeedbackDraw = false;  // vkCmdDrawIndirectByteCountEXT
  bool geometryStreams = false;
  uint32_t maxTransformFeedbackStreams = 0;
  uint32_t maxTransformFeedbackBuffers = 0;
  bool rasterizationStreamSelect = false;
  bool customBorderColor = false;
  bool vertexAttributeDivisor = false;
  bool depthClipEnable = false;
  bool nullDescriptor = false;  // VK_EXT_robustness2: unbound slots read zero, as in D3D11
  bool geometryShader = false;
  bool tessellationShader = false;
  bool pipelineStatistics = false;
  bool dualSourceBlend = false;
  bool fragmentStoresAndAtomics = false;        // pixel-shader UAVs
  bool vertexPipelineStoresAndAtomics = false;  // UAVs in VS, HS, DS, GS
  bool sampleRateShading = false;  // SV_SampleIndex / per-sample pixel shaders
  bool imageViewMinLod = false;    // VK_EXT_image_view_min_lod: SetResourceMinLOD's fractional clamp
  float timestampPeriodNs = 1.0f;
  VkPhysicalDeviceLimits limits{};
};

class Gpu {
 public:
  static HRESULT Create(const DEVICE_OPTIONS& options, std::unique_ptr<Gpu>* gpu);
  ~Gpu();
  Gpu(const Gpu&) = delete;
  Gpu& operator=(const Gpu&) = delete;

  VkDevice Device() const { return device_; }
  VkPhysicalDevice Physical() const { return physical_; }
  VkInstance Instance() const { return instance_; }
  VkQueue Queue() const { return queue_; }
  uint32_t QueueFamily() const { return queueFamily_; }
  const GpuCapabilities& Caps() const { return caps_; }
  const std::string& AdapterName() const { return adapterName_; }
  bool NativeDrawAuto() const { return nativeDrawAuto_; }
  // The validation layer (the D3D11 debug layer's counterpart) is on.
  bool Validating() const { return messenger_ != VK_NULL_HANDLE; }
  // Vulkan reported VK_ERROR_DEVICE_LOST: nothing more completes, and waits return at once.
  bool DeviceLost() const { return deviceLost_; }
  // Names a Vulkan object for debuggers and validation messages (VK_EXT_debug_utils; private_data.cpp).
  void SetObjectName(VkObjectType type, uint64_t handle, const std::string& name) const;

  // Reports a refusal or a validation message to the application.
  void Report(MESSAGE_CATEGORY category, MESSAGE_SEVERITY severity, const std::string& text) const;
  // Reports a refused call (the D3D11 debug layer's STATE_CREATION error) and returns E_INVALIDARG.
  HRESULT Refuse(const std::string& reason) const;

  // Memory
  uint32_t FindMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required) const;
  VkResult AllocateFor(VkMemoryRequirements requirements, VkMemoryPropertyFlags properties,
                       VkDeviceMemory* memory) const;
  bool IsFormatSupported(VkFormat format, VkFormatFeatureFlags2 features, bool optimalTiling = true) const;
  // The sample counts an image of `info` (format, type, tiling, usage, flags) may
  // have; 0 when the device cannot create it at all.
  VkSampleCountFlags ImageSampleCounts(const VkImageCreateInfo& info) const;

  // Submission. Commands are recorded into the current command buffer; each
  // submission gets a serial, and resources remember the serial of their last use.
  VkCommandBuffer Commands() { return recording_ ? recording_->commands : BeginCommands(); }
  uint64_t RecordingSerial() const { return recordingSerial_; }
  bool HasPendingCommands() const { return recording_ != nullptr; }
  void Submit();
  bool IsComplete(uint64_t serial);
  void WaitFor(uint64_t serial);
  void WaitIdle();
  // Runs `destroy` once the GPU has finished everything recorded so far.
  void DeferDestroy(std::function<void()> destroy);

  // Extension entry points.
  PFN_vkCmdPushDescriptorSetKHR vkCmdPushDescriptorSetKHR = nullptr;
  PFN_vkCmdBindTransformFeedbackBuffersEXT vkCmdBindTransformFeedbackBuffersEXT = nullptr;
  PFN_vkCmdBeginTransformFeedbackEXT vkCmdBeginTransformFeedbackEXT = nullptr;
  PFN_vkCmdEndTransformFeedbackEXT vkCmdEndTransformFeedbackEXT = nullptr;
  PFN_vkCmdBeginQueryIndexedEXT vkCmdBeginQueryIndexedEXT = nullptr;
  PFN_vkCmdEndQueryIndexedEXT vkCmdEndQueryIndexedEXT = nullptr;
  PFN_vkCmdDrawIndirectByteCountEXT vkCmdDrawIndirectByteCountEXT = nullptr;
  // VK_EXT_debug_utils command labels: set only when the instance enabled the
  // extension (with the validation layer), else null.
  PFN_vkCmdBeginDebugUtilsLabelEXT vkCmdBeginDebugUtilsLabelEXT = nullptr;
  PFN_vkCmdEndDebugUtilsLabelEXT vkCmdEndDebugUtilsLabelEXT = nullptr;
  PFN_vkCmdInsertDebugUtilsLabelEXT vkCmdInsertDebugUtilsLabelEXT = nullptr;

 private:
  struct Submission {
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer commands = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    uint64_t serial = 0;
    std::vector<std::function<void()>> destroyWhenDone;
  };

  Gpu() = default;
  HRESULT CreateInstance(bool validation);
  HRESULT PickPhysicalDevice(const char* wantedName);
  HRESULT CreateLogicalDevice();
  void LoadExtensionEntryPoints();
  void LoadDebugLabelEntryPoints();  // context_annotations.cpp
  void RetireCompleted();
  std::unique_ptr<Submission> AcquireSubmission();
  // Starts recording into a recycled or new command buffer.
  VkCommandBuffer BeginCommands();

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  VkPhysicalDeviceMemoryProperties memoryProperties_{};
  GpuCapabilities caps_;
  std::string adapterName_;
  bool nativeDrawAuto_ = false;
  MessageCallback onMessage_;
  // DEVICE_OPTIONS::InstanceExtensions (window-system integration for swap chains).
  std::vector<const char*> instanceExtensions_;

  // The context's thread records and submits; objects released on any thread
  // defer their destruction (the device is free-threaded). The mutex guards
  // what both touch: changes of the submissions and their destroyWhenDone lists.
  std::mutex submissionMutex_;
  std::unique_ptr<Submission> recording_;
  std::deque<std::unique_ptr<Submission>> inFlight_;
  std::vector<std::unique_ptr<Submission>> idle_;
  uint64_t recordingSerial_ = 1;
  std::atomic<uint64_t> completedSerial_ = 0;
  // Read from any thread (GetDeviceRemovedReason; the device is free-threaded).
  std::atomic<bool> deviceLost_ = false;
  // Records a VK_ERROR_DEVICE_LOST (reported once).
  void NoteResult(VkResult result, const char* call);
};

}  // namespace rhi::vk
