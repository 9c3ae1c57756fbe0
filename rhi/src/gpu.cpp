#include "gpu.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "vk_check.h"

namespace rhi::vk {

const char* ResultName(VkResult result) {
  switch (result) {
    case VK_SUCCESS: return "VK_SUCCESS";
    case VK_NOT_READY: return "VK_NOT_READY";
    case VK_TIMEOUT: return "VK_TIMEOUT";
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
    case VK_ERROR_FORMAT_NOT_SUPPORTED: return "VK_ERROR_FORMAT_NOT_SUPPORTED";
    default: return "VkResult error";
  }
}

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool EnvFlag(const char* name) {
  const char* value = std::getenv(name);
  return value && value[0] == '1';
}

bool LayerAvailable(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  for (const auto& layer : layers)
    if (std::strcmp(layer.layerName, name) == 0) return true;
  return false;
}

bool HasExtension(const std::vector<VkExtensionProperties>& list, const char* name) {
  for (const auto& e : list)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

VKAPI_ATTR VkBool32 VKAPI_CALL OnValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  const auto* gpu = static_cast<const Gpu*>(user);
  MESSAGE_SEVERITY mapped = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? MESSAGE_SEVERITY_ERROR
                                                                                        : MESSAGE_SEVERITY_WARNING;
  gpu->Report(MESSAGE_CATEGORY_VULKAN_VALIDATION, mapped, data->pMessage ? data->pMessage : "");
  return VK_FALSE;
}

}  // namespace

HRESULT Gpu::Create(const DEVICE_OPTIONS& options, std::unique_ptr<Gpu>* out) {
  std::unique_ptr<Gpu> gpu(new Gpu());
  gpu->onMessage_ = options.OnMessage;
  gpu->nativeDrawAuto_ = options.NativeDrawAuto || EnvFlag("RHI_NATIVE_DRAW_AUTO");
#ifndef NDEBUG
  const bool validation = true;
#else
  const bool validation = options.EnableValidation || EnvFlag("RHI_VALIDATION");
#endif
  const char* wanted = options.AdapterName ? options.AdapterName : std::getenv("RHI_DEVICE");
  gpu->instanceExtensions_.assign(options.InstanceExtensions,
                                  options.InstanceExtensions + options.InstanceExtensionCount);
  HRESULT hr = gpu->CreateInstance(validation);
  if (SUCCEEDED(hr)) hr = gpu->PickPhysicalDevice(wanted);
  if (SUCCEEDED(hr)) hr = gpu->CreateLogicalDevice();
  if (FAILED(hr)) return hr;
  gpu->LoadExtensionEntryPoints();
  *out = std::move(gpu);
  return S_OK;
}

HRESULT Gpu::CreateInstance(bool validation) {
  if (validation && !LayerAvailable(kValidationLayer)) {
    Report(MESSAGE_CATEGORY_STATE_CREATION, MESSAGE_SEVERITY_WARNING,
           "validation requested but VK_LAYER_KHRONOS_validation is not installed (Debian: vulkan-validationlayers)");
    validation = false;
  }
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "rhi";
  app.pEngineName = "rhi";
  app.apiVersion = VK_API_VERSION_1_3;

  std::vector<const char*> layers;
  std::vector<const char*> extensions = instanceExtensions_;
  if (validation) {
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  // Synchronization validation catches missing barriers, the backend's main risk.
  VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;

  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pNext = validation ? &features : nullptr;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = static_cast<uint32_t>(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  VkResult result = vkCreateInstance(&info, nullptr, &instance_);
  if (result != VK_SUCCESS) {
    Report(MESSAGE_CATEGORY_STATE_CREATION, MESSAGE_SEVERITY_ERROR,
           std::string("vkCreateInstance failed: ") + ResultName(result));
    return ToHresult(result);
  }
  if (validation) {
    VkDebugUtilsMessengerCreateInfoEXT messenger{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
    messenger.pfnUserCallback = OnValidationMessage;
    messenger.pUserData = this;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    if (create) create(instance_, &messenger, nullptr, &messenger_);
    LoadDebugLabelEntryPoints();
  }
  return S_OK;
}

HRESULT Gpu::PickPhysicalDevice(const char* wantedName) {
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance_, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance_, &count, devices.data());
  std::string available;
  VkPhysicalDevice lavapipe = VK_NULL_HANDLE;
  for (VkPhysicalDevice candidate : devices) {
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(candidate, &properties);
    std::string_view name = properties.deviceName;
    available += (available.empty() ? "" : ", ") + std::string(name);
    if (properties.apiVersion < VK_API_VERSION_1_3) continue;
    if (wantedName && name.find(wantedName) != std::string_view::npos) {
      physical_ = candidate;
      break;
    }
    if (name.find("llvmpipe") != std::string_view::npos) lavapipe = candidate;
  }
  if (!physical_ && wantedName) {
    Report(MESSAGE_CATEGORY_STATE_CREATION, MESSAGE_SEVERITY_ERROR,
           std::string("no Vulkan 1.3 device named like \"") + wantedName + "\"; available: " + available);
    return DXGI_ERROR_UNSUPPORTED;
  }
  if (!physical_) physical_ = lavapipe;
  if (!physical_) {
    Report(MESSAGE_CATEGORY_STATE_CREATION, MESSAGE_SEVERITY_ERROR,
           "no Vulkan 1.3 device (lavapipe: Debian package mesa-vulkan-drivers); available: " + available);
    return DXGI_ERROR_UNSUPPORTED;
  }
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(physical_, &properties);
  adapterName_ = properties.deviceName;
  caps_.limits = properties.limits;
  caps_.timestampPeriodNs = properties.limits.timestampPeriod;
  vkGetPhysicalDeviceMemoryProperties(physical_, &memoryProperties_);

  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &familyCount, families.data());
  for (uint32_t i = 0; i < familyCount; ++i) {
    if ((families[i].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) ==
        (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) {
      queueFamily_ = i;
      return S_OK;
    }
  }
  Report(MESSAGE_CATEGORY_STATE_CREATION, MESSAGE_SEVERITY_ERROR, adapterName_ + " has no graphics+compute queue");
  return DXGI_ERROR_UNSUPPORTED;
}

HRESULT Gpu::CreateLogicalDevice() {
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(physical_, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> available(count);
  vkEnumerateDeviceExtensionProperties(physical_, nullptr, &count, available.data());
  if (!HasExtension(available, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME)) {
    Report(MESSAGE_CATEGORY_STATE_CREATION, MESSAGE_SEVERITY_ERROR, adapterName_ + " lacks VK_KHR_push_descriptor");
    return DXGI_ERROR_UNSUPPORTED;
  }
  std::vector<const char*> extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
  auto enableIfPresent = [&](const char* name) {
    bool present = HasExtension(available, name);
    if (present) extensions.push_back(name);
    return present;
  };

  // Query what optional features exist, then enable exactly those.
  VkPhysicalDeviceTransformFeedbackFeaturesEXT xfb{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TRANSFORM_FEEDBACK_FEATURES_EXT};
  VkPhysicalDeviceRobustness2FeaturesEXT robustness{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ROBUSTNESS_2_FEATURES_EXT};
  VkPhysicalDeviceCustomBorderColorFeaturesEXT border{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_CUSTOM_BORDER_COLOR_FEATURES_EXT};
  VkPhysicalDeviceDepthClipEnableFeaturesEXT depthClip{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DEPTH_CLIP_ENABLE_FEATURES_EXT};
  VkPhysicalDeviceVertexAttributeDivisorFeaturesEXT divisor{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VERTEX_ATTRIBUTE_DIVISOR_FEATURES_EXT};
  VkPhysicalDeviceImageViewMinLodFeaturesEXT minLod{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_IMAGE_VIEW_MIN_LOD_FEATURES_EXT};
  VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceVulkan11Features v11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  v12.pNext = &v11;
  v13.pNext = &v12;
  supported.pNext = &v13;
  void** tail = &v11.pNext;
  auto chainIf = [&](bool present, auto& feature) {
    if (!present) return;
    *tail = &feature;
    tail = &feature.pNext;
  };
  // rhi/swap_chain.h; VK_KHR_swapchain needs the instance's VK_KHR_surface.
  for (const char* name : instanceExtensions_)
    if (std::strcmp(name, VK_KHR_SURFACE_EXTENSION_NAME) == 0) enableIfPresent(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  chainIf(enableIfPresent(VK_EXT_TRANSFORM_FEEDBACK_EXTENSION_NAME), xfb);
  chainIf(enableIfPresent(VK_EXT_ROBUSTNESS_2_EXTENSION_NAME), robustness);
  chainIf(enableIfPresent(VK_EXT_CUSTOM_BORDER_COLOR_EXTENSION_NAME), border);
  chainIf(enableIfPresent(VK_EXT_DEPTH_CLIP_ENABLE_EXTENSION_NAME), depthClip);
  chainIf(enableIfPresent(VK_EXT_VERTEX_ATTRIBUTE_DIVISOR_EXTENSION_NAME), divisor);
  chainIf(enableIfPresent(VK_EXT_IMAGE_VIEW_MIN_LOD_EXTENSION_NAME), minLod);
  vkGetPhysicalDeviceFeatures2(physical_, &supported);

  if (!v13.dynamicRendering || !v13.synchronization2) {
    Report(MESSAGE_CATEGORY_STATE_CREATION, MESSAGE_SEVERITY_ERROR,
           adapterName_ + " lacks dynamicRendering or synchronization2");
    return DXGI_ERROR_UNSUPPORTED;
  }
  // Turn off what the backend never uses so validation does not demand it.
  robustness.robustBufferAccess2 = VK_FALSE;
  robustness.robustImageAccess2 = VK_FALSE;
  supported.features.robustBufferAccess = VK_FALSE;
  border.customBorderColorWithoutFormat = border.customBorderColors;
  caps_.transformFeedback = xfb.transformFeedback;
  caps_.geometryStreams = xfb.geometryStreams;
  caps_.nullDescriptor = robustness.nullDescriptor;
  caps_.customBorderColor = border.customBorderColors;
  caps_.depthClipEnable = depthClip.depthClipEnable;
  caps_.vertexAttributeDivisor = divisor.vertexAttributeInstanceRateDivisor;
  caps_.geometryShader = supported.features.geometryShader;
  caps_.tessellationShader = supported.features.tessellationShader;
  caps_.pipelineStatistics = supported.features.pipelineStatisticsQuery;
  caps_.dualSourceBlend = supported.features.dualSrcBlend;
  caps_.fragmentStoresAndAtomics = supported.features.fragmentStoresAndAtomics;
  caps_.vertexPipelineStoresAndAtomics = supported.features.vertexPipelineStoresAndAtomics;
  caps_.sampleRateShading = supported.features.sampleRateShading;
  caps_.imageViewMinLod = minLod.minLod;

  if (caps_.transformFeedback) {
    VkPhysicalDeviceTransformFeedbackPropertiesEXT xfbProps{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TRANSFORM_FEEDBACK_PROPERTIES_EXT};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props.pNext = &xfbProps;
    vkGetPhysicalDeviceProperties2(physical_, &props);
    caps_.transformFeedbackQueries = xfbProps.transformFeedbackQueries;
    caps_.transformFeedbackDraw = xfbProps.transformFeedbackDraw;
    caps_.maxTransformFeedbackStreams = xfbProps.maxTransformFeedbackStreams;
    caps_.maxTransformFeedbackBuffers = xfbProps.maxTransformFeedbackBuffers;
    caps_.rasterizationStreamSelect = xfbProps.transformFeedbackRasterizationStreamSelect;
  }

  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = queueFamily_;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.pNext = &supported;
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queueInfo;
  info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  VkResult result = vkCreateDevice(physical_, &info, nullptr, &device_);
  if (result != VK_SUCCESS) {
    Report(MESSAGE_CATEGORY_STATE_CREATION, MESSAGE_SEVERITY_ERROR,
           std::string("vkCreateDevice failed: ") + ResultName(result));
    return ToHresult(result);
  }
  vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
  return S_OK;
}

void Gpu::LoadExtensionEntryPoints() {
  auto load = [&](auto& fn, const char* name) {
    fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(vkGetDeviceProcAddr(device_, name));
  };
  load(vkCmdPushDescriptorSetKHR, "vkCmdPushDescriptorSetKHR");
  if (!caps_.transformFeedback) return;
  load(vkCmdBindTransformFeedbackBuffersEXT, "vkCmdBindTransformFeedbackBuffersEXT");
  load(vkCmdBeginTransformFeedbackEXT, "vkCmdBeginTransformFeedbackEXT");
  load(vkCmdEndTransformFeedbackEXT, "vkCmdEndTransformFeedbackEXT");
  load(vkCmdBeginQueryIndexedEXT, "vkCmdBeginQueryIndexedEXT");
  load(vkCmdEndQueryIndexedEXT, "vkCmdEndQueryIndexedEXT");
  load(vkCmdDrawIndirectByteCountEXT, "vkCmdDrawIndirectByteCountEXT");
}

Gpu::~Gpu() {
  if (device_) {
    if (recording_) Submit();
    WaitIdle();
    for (auto* list : {&idle_}) {
      for (auto& s : *list) {
        vkDestroyFence(device_, s->fence, nullptr);
        vkDestroyCommandPool(device_, s->pool, nullptr);
      }
    }
    vkDestroyDevice(device_, nullptr);
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
}

void Gpu::Report(MESSAGE_CATEGORY category, MESSAGE_SEVERITY severity, const std::string& text) const {
  if (onMessage_) {
    onMessage_(category, severity, text.c_str());
    return;
  }
  std::fprintf(stderr, "rhi: %s\n", text.c_str());
}

HRESULT Gpu::Refuse(const std::string& reason) const {
  Report(MESSAGE_CATEGORY_STATE_CREATION, MESSAGE_SEVERITY_ERROR, reason);
  return E_INVALIDARG;
}

uint32_t Gpu::FindMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required) const {
  for (uint32_t i = 0; i < memoryProperties_.memoryTypeCount; ++i) {
    if ((typeBits & (1u << i)) && (memoryProperties_.memoryTypes[i].propertyFlags & required) == required) return i;
  }
  return UINT32_MAX;
}

VkResult Gpu::AllocateFor(VkMemoryRequirements requirements, VkMemoryPropertyFlags properties,
                          VkDeviceMemory* memory) const {
  uint32_t type = FindMemoryType(requirements.memoryTypeBits, properties);
  if (type == UINT32_MAX) return VK_ERROR_OUT_OF_DEVICE_MEMORY;
  VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  info.allocationSize = requirements.size;
  info.memoryTypeIndex = type;
  return vkAllocateMemory(device_, &info, nullptr, memory);
}

bool Gpu::IsFormatSupported(VkFormat format, VkFormatFeatureFlags2 features, bool optimalTiling) const {
  VkFormatProperties3 props3{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_3};
  VkFormatProperties2 props{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_2};
  props.pNext = &props3;
  vkGetPhysicalDeviceFormatProperties2(physical_, format, &props);
  VkFormatFeatureFlags2 have = optimalTiling ? props3.optimalTilingFeatures : props3.bufferFeatures;
  return (have & features) == features;
}

VkSampleCountFlags Gpu::ImageSampleCounts(const VkImageCreateInfo& info) const {
  VkPhysicalDeviceImageFormatInfo2 query{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_IMAGE_FORMAT_INFO_2};
  // A format list narrows what a mutable-format image may be viewed as, and so what it supports.
  query.pNext = info.pNext;
  query.format = info.format;
  query.type = info.imageType;
  query.tiling = info.tiling;
  query.usage = info.usage;
  query.flags = info.flags;
  VkImageFormatProperties2 properties{VK_STRUCTURE_TYPE_IMAGE_FORMAT_PROPERTIES_2};
  if (vkGetPhysicalDeviceImageFormatProperties2(physical_, &query, &properties) != VK_SUCCESS) return 0;
  return properties.imageFormatProperties.sampleCounts;
}

std::unique_ptr<Gpu::Submission> Gpu::AcquireSubmission() {
  RetireCompleted();
  {
    std::lock_guard lock(submissionMutex_);
    if (!idle_.empty()) {
      auto s = std::move(idle_.back());
      idle_.pop_back();
      return s;
    }
  }
  auto s = std::make_unique<Submission>();
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  poolInfo.queueFamilyIndex = queueFamily_;
  vkCreateCommandPool(device_, &poolInfo, nullptr, &s->pool);
  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = s->pool;
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  vkAllocateCommandBuffers(device_, &allocInfo, &s->commands);
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  vkCreateFence(device_, &fenceInfo, nullptr, &s->fence);
  return s;
}

VkCommandBuffer Gpu::BeginCommands() {
  std::unique_ptr<Submission> submission = AcquireSubmission();
  submission->serial = recordingSerial_;
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(submission->commands, &begin);
  std::lock_guard lock(submissionMutex_);
  recording_ = std::move(submission);
  return recording_->commands;
}

void Gpu::Submit() {
  if (!recording_) return;
  vkEndCommandBuffer(recording_->commands);
  VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cmdInfo.commandBuffer = recording_->commands;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmdInfo;
  VkResult result = vkQueueSubmit2(queue_, 1, &submit, recording_->fence);
  if (result != VK_SUCCESS)
    Report(MESSAGE_CATEGORY_EXECUTION, MESSAGE_SEVERITY_CORRUPTION,
           std::string("vkQueueSubmit2 failed: ") + ResultName(result));
  NoteResult(result, "vkQueueSubmit2");
  std::lock_guard lock(submissionMutex_);
  inFlight_.push_back(std::move(recording_));
  ++recordingSerial_;
}

void Gpu::RetireCompleted() {
  for (;;) {
    std::unique_ptr<Submission> done;
    {
      std::lock_guard lock(submissionMutex_);
      if (inFlight_.empty() || vkGetFenceStatus(device_, inFlight_.front()->fence) != VK_SUCCESS) return;
      done = std::move(inFlight_.front());
      inFlight_.pop_front();
      completedSerial_ = done->serial;
    }
    // Outside the lock: a destruction may defer another.
    for (auto& destroy : done->destroyWhenDone) destroy();
    done->destroyWhenDone.clear();
    // Recycled as soon as the GPU is done with it, not when it is next needed:
    // the command memory goes back to the allocator while it is still warm
    // (lavapipe allocates every recorded command), and the next recording
    // reuses it from there.
    vkResetCommandPool(device_, done->pool, 0);
    vkResetFences(device_, 1, &done->fence);
    std::lock_guard lock(submissionMutex_);
    idle_.push_back(std::move(done));
  }
}

bool Gpu::IsComplete(uint64_t serial) {
  if (serial <= completedSerial_) return true;
  RetireCompleted();
  return serial <= completedSerial_;
}

void Gpu::WaitFor(uint64_t serial) {
  if (serial >= recordingSerial_ && recording_) Submit();
  // A lost device never signals its fences: the wait ends instead of hanging,
  // and GetDeviceRemovedReason says why.
  while (!deviceLost_ && !IsComplete(serial) && !inFlight_.empty()) {
    NoteResult(vkWaitForFences(device_, 1, &inFlight_.front()->fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    RetireCompleted();
  }
}

void Gpu::NoteResult(VkResult result, const char* call) {
  if (result != VK_ERROR_DEVICE_LOST || deviceLost_.exchange(true)) return;
  Report(MESSAGE_CATEGORY_EXECUTION, MESSAGE_SEVERITY_CORRUPTION,
         std::string(call) + " returned VK_ERROR_DEVICE_LOST: the device is removed "
                             "(GetDeviceRemovedReason returns DXGI_ERROR_DEVICE_REMOVED)");
}

void Gpu::WaitIdle() {
  if (recording_) Submit();
  if (!inFlight_.empty()) WaitFor(inFlight_.back()->serial);
}

void Gpu::DeferDestroy(std::function<void()> destroy) {
  {
    std::lock_guard lock(submissionMutex_);
    if (recording_) return recording_->destroyWhenDone.push_back(std::move(destroy));
    if (!inFlight_.empty()) return inFlight_.back()->destroyWhenDone.push_back(std::move(destroy));
  }
  destroy();
}

}  // namespace rhi::vk
