#include "raw_vulkan.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>
#include <vector>

#include "rhi/shader_bindings.h"
#include "spirv/patches.h"

namespace bench {

namespace {

void Check(VkResult result, const char* what) {
  if (result == VK_SUCCESS) return;
  std::fprintf(stderr, "rhi_bench (raw Vulkan): %s failed (VkResult %d)\n", what, static_cast<int>(result));
  std::exit(3);
}

bool HasExtension(const std::vector<VkExtensionProperties>& list, const char* name) {
  for (const auto& e : list)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

// The constant buffer's descriptor binding: VS b0, as the HLSL compiler numbers it.
constexpr uint32_t kConstantBufferBinding =
    rhi::BindingFor(rhi::ShaderStage::Vertex, rhi::RegisterClass::ConstantBuffer, 0);

// D3D11's viewport convention, as the RHI sets it: a negative height flips y.
constexpr VkViewport kViewport{0.0f, static_cast<float>(kTargetSize), static_cast<float>(kTargetSize),
                               -static_cast<float>(kTargetSize), 0.0f, 1.0f};
constexpr VkRect2D kScissor{{0, 0}, {kTargetSize, kTargetSize}};

}  // namespace

RawVulkan::RawVulkan(const SceneShaders& shaders) {
  CreateDevice();
  CreateResources();
  CreatePipelines(shaders);
}

RawVulkan::~RawVulkan() {
  if (!device_) return;
  vkDeviceWaitIdle(device_);
  for (VkPipeline pipeline : pipelines_) vkDestroyPipeline(device_, pipeline, nullptr);
  vkDestroyPipelineLayout(device_, layout_, nullptr);
  vkDestroyDescriptorSetLayout(device_, setLayout_, nullptr);
  for (VkBuffer buffer : vertexBuffers_) vkDestroyBuffer(device_, buffer, nullptr);
  for (VkBuffer buffer : constantBuffers_) vkDestroyBuffer(device_, buffer, nullptr);
  for (VkDeviceMemory memory : bufferMemory_) vkFreeMemory(device_, memory, nullptr);
  vkDestroyImageView(device_, targetView_, nullptr);
  vkDestroyImage(device_, target_, nullptr);
  vkFreeMemory(device_, targetMemory_, nullptr);
  vkDestroyFence(device_, fence_, nullptr);
  vkDestroyCommandPool(device_, pool_, nullptr);
  vkDestroyDevice(device_, nullptr);
  vkDestroyInstance(instance_, nullptr);
}

// Same device choice as the RHI: RHI_DEVICE (a name substring) if set, else
// lavapipe, else the first Vulkan 1.3 device.
void RawVulkan::CreateDevice() {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "rhi_bench_raw";
  app.apiVersion = VK_API_VERSION_1_3;
  VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  instanceInfo.pApplicationInfo = &app;
  // Check runs only (RHI_BENCH_RAW_VALIDATION=1): the Khronos validation layer
  // reports to stderr through its default callback. Never on for timing.
  const char* layer = "VK_LAYER_KHRONOS_validation";
  const char* validate = std::getenv("RHI_BENCH_RAW_VALIDATION");
  if (validate && validate[0] == '1') {
    instanceInfo.enabledLayerCount = 1;
    instanceInfo.ppEnabledLayerNames = &layer;
  }
  Check(vkCreateInstance(&instanceInfo, nullptr, &instance_), "vkCreateInstance");

  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance_, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance_, &count, devices.data());
  const char* wanted = std::getenv("RHI_DEVICE");
  VkPhysicalDevice lavapipe = VK_NULL_HANDLE, first = VK_NULL_HANDLE;
  for (VkPhysicalDevice candidate : devices) {
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(candidate, &properties);
    if (properties.apiVersion < VK_API_VERSION_1_3) continue;
    std::string_view name = properties.deviceName;
    if (wanted && name.find(wanted) != std::string_view::npos) {
      physical_ = candidate;
      break;
    }
    if (!lavapipe && name.find("llvmpipe") != std::string_view::npos) lavapipe = candidate;
    if (!first) first = candidate;
  }
  if (!physical_ && wanted) {
    std::fprintf(stderr, "rhi_bench (raw Vulkan): no Vulkan 1.3 device named like \"%s\"\n", wanted);
    std::exit(3);
  }
  if (!physical_) physical_ = lavapipe ? lavapipe : first;
  if (!physical_) {
    std::fprintf(stderr, "rhi_bench (raw Vulkan): no Vulkan 1.3 device\n");
    std::exit(3);
  }
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(physical_, &properties);
  deviceName_ = properties.deviceName;
  vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);

  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &familyCount, families.data());
  queueFamily_ = UINT32_MAX;
  for (uint32_t i = 0; i < familyCount && queueFamily_ == UINT32_MAX; ++i)
    if (families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) queueFamily_ = i;
  if (queueFamily_ == UINT32_MAX) {
    std::fprintf(stderr, "rhi_bench (raw Vulkan): %s has no graphics queue\n", deviceName_.c_str());
    std::exit(3);
  }

  uint32_t extensionCount = 0;
  vkEnumerateDeviceExtensionProperties(physical_, nullptr, &extensionCount, nullptr);
  std::vector<VkExtensionProperties> available(extensionCount);
  vkEnumerateDeviceExtensionProperties(physical_, nullptr, &extensionCount, available.data());
  if (!HasExtension(available, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME)) {
    std::fprintf(stderr, "rhi_bench (raw Vulkan): %s lacks VK_KHR_push_descriptor\n", deviceName_.c_str());
    std::exit(3);
  }
  const char* extensions[] = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};

  // Vulkan 1.3 core: dynamic rendering, synchronization2; the extended dynamic
  // state commands (viewport/scissor with count, topology, primitive restart,
  // vertex binding stride) are core 1.3 commands and need no feature bit.
  VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  v13.dynamicRendering = VK_TRUE;
  v13.synchronization2 = VK_TRUE;
  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = queueFamily_;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  deviceInfo.pNext = &v13;
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  deviceInfo.enabledExtensionCount = 1;
  deviceInfo.ppEnabledExtensionNames = extensions;
  Check(vkCreateDevice(physical_, &deviceInfo, nullptr, &device_), "vkCreateDevice");
  vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
  vkCmdPushDescriptorSetKHR_ =
      reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(vkGetDeviceProcAddr(device_, "vkCmdPushDescriptorSetKHR"));

  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  poolInfo.queueFamilyIndex = queueFamily_;
  Check(vkCreateCommandPool(device_, &poolInfo, nullptr, &pool_), "vkCreateCommandPool");
  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = pool_;
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  Check(vkAllocateCommandBuffers(device_, &allocInfo, &commands_), "vkAllocateCommandBuffers");
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  Check(vkCreateFence(device_, &fenceInfo, nullptr, &fence_), "vkCreateFence");
}

uint32_t RawVulkan::FindMemoryType(uint32_t typeBits, VkMemoryPropertyFlags flags) const {
  for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
    if ((typeBits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & flags) == flags) return i;
  std::fprintf(stderr, "rhi_bench (raw Vulkan): no memory type with flags 0x%x\n", flags);
  std::exit(3);
}

VkBuffer RawVulkan::CreateHostBuffer(VkBufferUsageFlags usage, const void* data, VkDeviceSize size,
                                     VkDeviceMemory* memory) {
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buffer = VK_NULL_HANDLE;
  Check(vkCreateBuffer(device_, &info, nullptr, &buffer), "vkCreateBuffer");
  VkMemoryRequirements requirements;
  vkGetBufferMemoryRequirements(device_, buffer, &requirements);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = requirements.size;
  alloc.memoryTypeIndex = FindMemoryType(requirements.memoryTypeBits,
                                         VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  Check(vkAllocateMemory(device_, &alloc, nullptr, memory), "vkAllocateMemory");
  Check(vkBindBufferMemory(device_, buffer, *memory, 0), "vkBindBufferMemory");
  void* mapped = nullptr;
  Check(vkMapMemory(device_, *memory, 0, size, 0, &mapped), "vkMapMemory");
  std::memcpy(mapped, data, size);
  vkUnmapMemory(device_, *memory);
  return buffer;
}

void RawVulkan::CreateResources() {
  VkImageCreateInfo imageInfo{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  imageInfo.imageType = VK_IMAGE_TYPE_2D;
  imageInfo.format = VK_FORMAT_R8G8B8A8_UNORM;
  imageInfo.extent = {kTargetSize, kTargetSize, 1};
  imageInfo.mipLevels = 1;
  imageInfo.arrayLayers = 1;
  imageInfo.samples = VK_SAMPLE_COUNT_1_BIT;
  imageInfo.tiling = VK_IMAGE_TILING_OPTIMAL;
  imageInfo.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  imageInfo.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  imageInfo.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  Check(vkCreateImage(device_, &imageInfo, nullptr, &target_), "vkCreateImage");
  VkMemoryRequirements requirements;
  vkGetImageMemoryRequirements(device_, target_, &requirements);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = requirements.size;
  alloc.memoryTypeIndex = FindMemoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  Check(vkAllocateMemory(device_, &alloc, nullptr, &targetMemory_), "vkAllocateMemory");
  Check(vkBindImageMemory(device_, target_, targetMemory_, 0), "vkBindImageMemory");
  VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  viewInfo.image = target_;
  viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
  viewInfo.format = VK_FORMAT_R8G8B8A8_UNORM;
  viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  Check(vkCreateImageView(device_, &viewInfo, nullptr, &targetView_), "vkCreateImageView");

  for (int i = 0; i < 2; ++i) {
    vertexBuffers_[i] = CreateHostBuffer(VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, kTriangles[i], sizeof kTriangles[i],
                                         &bufferMemory_[i]);
    constantBuffers_[i] = CreateHostBuffer(VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, &kConstants[i], sizeof kConstants[i],
                                           &bufferMemory_[2 + i]);
  }

  // The target's one layout transition, then it stays COLOR_ATTACHMENT_OPTIMAL.
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  Check(vkBeginCommandBuffer(commands_, &begin), "vkBeginCommandBuffer");
  VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  barrier.srcStageMask = VK_PIPELINE_STAGE_2_NONE;
  barrier.dstStageMask = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
  barrier.dstAccessMask = VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
  barrier.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  barrier.newLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = target_;
  barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.imageMemoryBarrierCount = 1;
  dependency.pImageMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(commands_, &dependency);
  EndSubmitAndWait();
}

void RawVulkan::CreatePipelines(const SceneShaders& shaders) {
  // One push-descriptor set: the VS constant buffer at its HLSL binding.
  VkDescriptorSetLayoutBinding binding{kConstantBufferBinding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1,
                                       VK_SHADER_STAGE_VERTEX_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
  setInfo.bindingCount = 1;
  setInfo.pBindings = &binding;
  Check(vkCreateDescriptorSetLayout(device_, &setInfo, nullptr, &setLayout_), "vkCreateDescriptorSetLayout");
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &setLayout_;
  Check(vkCreatePipelineLayout(device_, &layoutInfo, nullptr, &layout_), "vkCreatePipelineLayout");

  // The compiler's SPIR-V carries SPV_GOOGLE_hlsl_functionality1 UserSemantic
  // decorations; strip them with the RHI's own pass (drivers without
  // VK_GOOGLE_hlsl_functionality1 reject them).
  auto createModule = [&](const std::vector<uint32_t>& words) {
    rhi::spirv::WordsResult stripped = rhi::spirv::StripHlslDecorations(words);
    if (!stripped) {
      std::fprintf(stderr, "rhi_bench (raw Vulkan): StripHlslDecorations: %s\n", stripped.error.c_str());
      std::exit(3);
    }
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = stripped->size() * sizeof(uint32_t);
    info.pCode = stripped->data();
    VkShaderModule module = VK_NULL_HANDLE;
    Check(vkCreateShaderModule(device_, &info, nullptr, &module), "vkCreateShaderModule");
    return module;
  };

  VkVertexInputBindingDescription vertexBinding{0, kVertexStride, VK_VERTEX_INPUT_RATE_VERTEX};
  VkVertexInputAttributeDescription position{0, 0, VK_FORMAT_R32G32_SFLOAT, 0};  // POSITION, location 0
  VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vertexInput.vertexBindingDescriptionCount = 1;
  vertexInput.pVertexBindingDescriptions = &vertexBinding;
  vertexInput.vertexAttributeDescriptionCount = 1;
  vertexInput.pVertexAttributeDescriptions = &position;
  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_BACK_BIT;  // D3D11 default rasterizer state
  raster.frontFace = VK_FRONT_FACE_CLOCKWISE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  const VkSampleMask sampleMask = 0xFFFFFFFFu;
  multisample.pSampleMask = &sampleMask;
  VkPipelineDepthStencilStateCreateInfo depthStencil{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  // The same dynamic state the RHI's rasterizing pipelines declare.
  const VkDynamicState dynamicStates[] = {
      VK_DYNAMIC_STATE_STENCIL_REFERENCE,         VK_DYNAMIC_STATE_BLEND_CONSTANTS,
      VK_DYNAMIC_STATE_PRIMITIVE_TOPOLOGY,        VK_DYNAMIC_STATE_PRIMITIVE_RESTART_ENABLE,
      VK_DYNAMIC_STATE_VERTEX_INPUT_BINDING_STRIDE, VK_DYNAMIC_STATE_VIEWPORT_WITH_COUNT,
      VK_DYNAMIC_STATE_SCISSOR_WITH_COUNT};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = static_cast<uint32_t>(std::size(dynamicStates));
  dynamic.pDynamicStates = dynamicStates;
  const VkFormat colorFormat = VK_FORMAT_R8G8B8A8_UNORM;
  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachmentFormats = &colorFormat;

  for (int pair = 0; pair < 2; ++pair) {
    VkShaderModule vs = createModule(shaders.vs[pair]);
    VkShaderModule ps = createModule(shaders.ps[pair]);
    VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                 {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vs;
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = ps;
    stages[1].pName = "main";
    for (int blend = 0; blend < 2; ++blend) {
      VkPipelineColorBlendAttachmentState attachment{};
      attachment.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                                  VK_COLOR_COMPONENT_A_BIT;
      if (blend == 1) {
        attachment.blendEnable = VK_TRUE;
        attachment.srcColorBlendFactor = attachment.srcAlphaBlendFactor = VK_BLEND_FACTOR_CONSTANT_COLOR;
        attachment.dstColorBlendFactor = attachment.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_CONSTANT_COLOR;
        attachment.colorBlendOp = attachment.alphaBlendOp = VK_BLEND_OP_ADD;
      }
      VkPipelineColorBlendStateCreateInfo colorBlend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
      colorBlend.attachmentCount = 1;
      colorBlend.pAttachments = &attachment;
      VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
      info.pNext = &rendering;
      info.stageCount = 2;
      info.pStages = stages;
      info.pVertexInputState = &vertexInput;
      info.pInputAssemblyState = &assembly;
      info.pViewportState = &viewport;
      info.pRasterizationState = &raster;
      info.pMultisampleState = &multisample;
      info.pDepthStencilState = &depthStencil;
      info.pColorBlendState = &colorBlend;
      info.pDynamicState = &dynamic;
      info.layout = layout_;
      Check(vkCreateGraphicsPipelines(device_, VK_NULL_HANDLE, 1, &info, nullptr, &pipelines_[pair * 2 + blend]),
            "vkCreateGraphicsPipelines");
    }
    vkDestroyShaderModule(device_, vs, nullptr);
    vkDestroyShaderModule(device_, ps, nullptr);
  }
}

void RawVulkan::SetPassState(VkCommandBuffer commands) {
  vkCmdSetViewportWithCount(commands, 1, &kViewport);
  vkCmdSetScissorWithCount(commands, 1, &kScissor);
  vkCmdSetPrimitiveTopology(commands, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST);
  vkCmdSetPrimitiveRestartEnable(commands, VK_FALSE);
}

void RawVulkan::RecordBatch(int draws, bool reemitDynamicState) { Record(draws, reemitDynamicState); }

void RawVulkan::Warmup() {
  Record(kDrawsPerBatch, false);
  SubmitAndWait();
}

void RawVulkan::Record(int draws, bool reemitDynamicState) {
  VkCommandBuffer commands = commands_;
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(commands, &begin);

  // The previous batch's colour writes before this batch's.
  VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  barrier.srcStageMask = barrier.dstStageMask = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
  barrier.srcAccessMask = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.memoryBarrierCount = 1;
  dependency.pMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(commands, &dependency);

  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = targetView_;
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
  rendering.renderArea = kScissor;
  rendering.layerCount = 1;
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachments = &color;
  vkCmdBeginRendering(commands, &rendering);

  // Set once per pass: every pipeline declares these dynamic, so binding
  // another pipeline keeps them.
  SetPassState(commands);

  for (int i = 0; i < draws; ++i) {
    const DrawChoice c = ChoiceFor(i);
    // OMSetBlendState + VSSetShader/PSSetShader (+ OMSetDepthStencilState) -> pipeline.
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines_[c.pair * 2 + c.blend]);
    if (reemitDynamicState) SetPassState(commands);
    // OMSetBlendState's blend factor, OMSetDepthStencilState's stencil ref.
    vkCmdSetBlendConstants(commands, kBlendFactors[c.blend]);
    vkCmdSetStencilReference(commands, VK_STENCIL_FACE_FRONT_AND_BACK, kStencilRefs[c.pair]);
    // IASetVertexBuffers.
    const VkDeviceSize offset = 0, stride = kVertexStride;
    vkCmdBindVertexBuffers2(commands, 0, 1, &vertexBuffers_[c.vb], &offset, nullptr, &stride);
    // VSSetConstantBuffers.
    VkDescriptorBufferInfo bufferInfo{constantBuffers_[c.cb], 0, sizeof(DrawConstants)};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstBinding = kConstantBufferBinding;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    write.pBufferInfo = &bufferInfo;
    vkCmdPushDescriptorSetKHR_(commands, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &write);
    // Draw(3, 0).
    vkCmdDraw(commands, 3, 1, 0, 0);
  }
}

void RawVulkan::SubmitAndWait() {
  vkCmdEndRendering(commands_);
  EndSubmitAndWait();
}

void RawVulkan::EndSubmitAndWait() {
  Check(vkEndCommandBuffer(commands_), "vkEndCommandBuffer");
  VkCommandBufferSubmitInfo commandInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  commandInfo.commandBuffer = commands_;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &commandInfo;
  Check(vkQueueSubmit2(queue_, 1, &submit, fence_), "vkQueueSubmit2");
  Check(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  Check(vkResetFences(device_, 1, &fence_), "vkResetFences");
  // Recycle the command memory once the GPU is done with it, outside the timed
  // recording - as the RHI does (it resets a pool when it acquires the next
  // submission, which happens in its untimed Flush/Map path).
  Check(vkResetCommandPool(device_, pool_, 0), "vkResetCommandPool");
}

}  // namespace bench
