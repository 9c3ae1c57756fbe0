#include "pipelines.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <map>
#include <optional>
#include <type_traits>

#include "draw_auto_args.spv.h"
#include "shaders.h"
#include "spirv/patches.h"
#include "spirv/spirv_module.h"
#include "vk_check.h"
#include "states/blend.h"
#include "states/depth_stencil.h"
#include "states/formats.h"
#include "states/input_layout.h"
#include "states/rasterizer.h"

namespace rhi::vk {

static_assert(std::has_unique_object_representations_v<GraphicsPipelineKey>,
              "GraphicsPipelineKey is hashed bytewise: it must have no padding");

static_assert(sizeof(GraphicsPipelineKey) % sizeof(uint64_t) == 0);

namespace {

constexpr size_t kKeyWords = sizeof(GraphicsPipelineKey) / sizeof(uint64_t);

// One odd multiplier per key word (splitmix64 of the word index).
constexpr std::array<uint64_t, kKeyWords> kKeyWordMultipliers = [] {
  std::array<uint64_t, kKeyWords> multipliers{};
  for (size_t i = 0; i < kKeyWords; ++i) {
    uint64_t z = (i + 1) * 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    multipliers[i] = (z ^ (z >> 31)) | 1;
  }
  return multipliers;
}();

}  // namespace

size_t GraphicsPipelineKeyHash::operator()(const GraphicsPipelineKey& key) const {
  // Word at a time (the key is padding-free and 8-byte aligned), each word
  // multiplied independently so the products do not wait on each other (a
  // lookup per pipeline change is on the draw path), then one final mix.
  uint64_t words[kKeyWords];
  std::memcpy(words, &key, sizeof key);
  uint64_t hash = 0;
  for (size_t i = 0; i < kKeyWords; ++i) hash += words[i] * kKeyWordMultipliers[i];
  hash ^= hash >> 32;
  hash *= 0xD6E8FEB86659FD93ull;
  hash ^= hash >> 32;
  return static_cast<size_t>(hash);
}

GraphicsPipelineKey DefaultPipelineKey() {
  GraphicsPipelineKey key;
  key.sampleMask = DEFAULT_SAMPLE_MASK;
  key.topologyClass = TopologyClass(PRIMITIVE_TOPOLOGY_UNDEFINED);
  return key;
}

uint32_t TopologyClass(PRIMITIVE_TOPOLOGY topology) {
  if (topology >= PRIMITIVE_TOPOLOGY_1_CONTROL_POINT_PATCHLIST) return 100 + (topology - 32);
  switch (topology) {
    case PRIMITIVE_TOPOLOGY_POINTLIST: return VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
    case PRIMITIVE_TOPOLOGY_LINELIST:
    case PRIMITIVE_TOPOLOGY_LINESTRIP:
    case PRIMITIVE_TOPOLOGY_LINELIST_ADJ:
    case PRIMITIVE_TOPOLOGY_LINESTRIP_ADJ: return VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
    default: return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  }
}

PipelineCache::PipelineCache(Gpu& gpu) : gpu_(gpu) {}

PipelineCache::~PipelineCache() {
  VkDevice device = gpu_.Device();
  for (auto& [key, pipeline] : graphics_) vkDestroyPipeline(device, pipeline->pipeline, nullptr);
  for (auto& [key, pipeline] : compute_) vkDestroyPipeline(device, pipeline->pipeline, nullptr);
  if (drawAutoArgs_) vkDestroyPipeline(device, drawAutoArgs_->pipeline, nullptr);
  for (auto& [key, layout] : layouts_) {
    vkDestroyPipelineLayout(device, layout->layout, nullptr);
    vkDestroyDescriptorSetLayout(device, layout->setLayout, nullptr);
  }
}

VkShaderModule PipelineCache::CreateModule(const std::vector<uint32_t>& words) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = words.size() * sizeof(uint32_t);
  info.pCode = words.data();
  VkShaderModule module = VK_NULL_HANDLE;
  vkCreateShaderModule(gpu_.Device(), &info, nullptr, &module);
  return module;
}

const PipelineLayout* PipelineCache::Layout(const std::vector<VkDescriptorSetLayoutBinding>& bindings,
                                            uint32_t pushConstantBytes) {
  std::string key(reinterpret_cast<const char*>(&pushConstantBytes), sizeof pushConstantBytes);
  for (const auto& b : bindings) {
    const uint32_t fields[] = {b.binding, static_cast<uint32_t>(b.descriptorType), b.descriptorCount, b.stageFlags};
    key.append(reinterpret_cast<const char*>(fields), sizeof fields);
  }
  auto& slot = layouts_[key];
  if (slot) return slot.get();
  auto layout = std::make_unique<PipelineLayout>();
  layout->bindings = bindings;
  for (const auto& b : bindings) layout->registers.push_back(RegisterOfBinding(b.binding));
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  // D3D11 rebinds per draw: push descriptors match that without pools.
  setInfo.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
  setInfo.bindingCount = static_cast<uint32_t>(bindings.size());
  setInfo.pBindings = bindings.data();
  vkCreateDescriptorSetLayout(gpu_.Device(), &setInfo, nullptr, &layout->setLayout);
  VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushConstantBytes};
  VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  info.setLayoutCount = 1;
  info.pSetLayouts = &layout->setLayout;
  info.pushConstantRangeCount = pushConstantBytes ? 1 : 0;
  info.pPushConstantRanges = &range;
  vkCreatePipelineLayout(gpu_.Device(), &info, nullptr, &layout->layout);
  slot = std::move(layout);
  return slot.get();
}

namespace {

VkShaderStageFlagBits VkStage(ShaderStage stage) {
  switch (stage) {
    case ShaderStage::Vertex: return VK_SHADER_STAGE_VERTEX_BIT;
    case ShaderStage::Hull: return VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT;
    case ShaderStage::Domain: return VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT;
    case ShaderStage::Geometry: return VK_SHADER_STAGE_GEOMETRY_BIT;
    case ShaderStage::Pixel: return VK_SHADER_STAGE_FRAGMENT_BIT;
    case ShaderStage::Compute: return VK_SHADER_STAGE_COMPUTE_BIT;
  }
  return VK_SHADER_STAGE_ALL;
}

VkDescriptorType ToVkDescriptorType(spirv::DescriptorKind kind) {
  switch (kind) {
    case spirv::DescriptorKind::UniformBuffer: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case spirv::DescriptorKind::StorageBuffer: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    case spirv::DescriptorKind::SampledImage: return VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
    case spirv::DescriptorKind::StorageImage: return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    case spirv::DescriptorKind::Sampler: return VK_DESCRIPTOR_TYPE_SAMPLER;
    case spirv::DescriptorKind::CombinedImageSampler: return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    case spirv::DescriptorKind::UniformTexelBuffer: return VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    case spirv::DescriptorKind::StorageTexelBuffer: return VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
    default: return VK_DESCRIPTOR_TYPE_MAX_ENUM;
  }
}

// The union of every stage's descriptor bindings, sorted by binding number.
std::vector<VkDescriptorSetLayoutBinding> CollectBindings(std::initializer_list<const ShaderCode*> shaders) {
  std::map<uint32_t, VkDescriptorSetLayoutBinding> merged;
  for (const ShaderCode* shader : shaders) {
    if (!shader) continue;
    for (const spirv::DescriptorBinding& b : shader->reflection.bindings) {
      auto [it, inserted] = merged.try_emplace(
          b.binding,
          VkDescriptorSetLayoutBinding{b.binding, ToVkDescriptorType(b.kind), std::max(1u, b.arrayCount), 0, nullptr});
      it->second.stageFlags |= VkStage(shader->stage);
    }
  }
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  for (auto& [binding, value] : merged) bindings.push_back(value);
  return bindings;
}


// Links `consumer`'s inputs to `producer`'s outputs by HLSL semantic: glslang
// numbers locations per stage in declaration order, D3D11 matches by name.
std::vector<uint32_t> LinkInputs(const spirv::Reflection& producer, const ShaderCode& consumer,
                                 std::vector<uint32_t> words) {
  std::map<std::string, uint32_t> produced;
  uint32_t nextFree = 0;
  for (const auto& out : producer.outputs) {
    if (!out.location || out.builtIn) continue;
    produced[out.Semantic()] = *out.location;
    nextFree = std::max(nextFree, *out.location + std::max(1u, out.locationCount));
  }
  std::map<uint32_t, uint32_t> remap;
  for (const auto& in : consumer.reflection.inputs) {
    if (!in.location || in.builtIn) continue;
    auto it = produced.find(in.Semantic());
    // An input nothing writes gets a location of its own (D3D11 reads it as undefined).
    uint32_t target = it != produced.end() ? it->second : nextFree++;
    remap[*in.location] = target;
  }
  return spirv::RemapLocations(words, spirv::StorageClass::Input, remap).value;
}

// Dual-source blending: D3D11's SV_Target1 is the second source of target 0;
// Vulkan wants it at Location 0, Index 1.
std::vector<uint32_t> MakeDualSourceOutput(const std::vector<uint32_t>& words) {
  constexpr uint32_t kOpVariable = 59, kOpDecorate = 71, kDecorationLocation = 30, kDecorationIndex = 32;
  constexpr uint32_t kStorageOutput = 3;
  spirv::Result<spirv::Module> parsed = spirv::Module::Parse(words);
  if (!parsed) return words;
  spirv::Module& module = *parsed;
  auto isOutput = [&](uint32_t id) {
    const spirv::Instruction* definition = module.Definition(id);
    return definition && definition->opcode() == kOpVariable && definition->operand(2) == kStorageOutput;
  };
  for (size_t i = 0; i < module.size(); ++i) {
    spirv::Instruction& decoration = module[i];
    if (decoration.opcode() != kOpDecorate || decoration.operand(1) != kDecorationLocation ||
        decoration.operand(2) != 1 || !isOutput(decoration.operand(0)))
      continue;
    decoration.setOperand(2, 0);
    module.Insert(i + 1, spirv::Instruction(kOpDecorate, {decoration.operand(0), kDecorationIndex, 1}));
    break;
  }
  return module.Assemble();
}

bool UsesDualSource(const BLEND_DESC& blend) {
  auto dual = [](BLEND b) { return b >= BLEND_SRC1_COLOR && b <= BLEND_INV_SRC1_ALPHA; };
  const auto& rt = blend.RenderTarget[0];
  return rt.BlendEnable && (dual(rt.SrcBlend) || dual(rt.DestBlend) || dual(rt.SrcBlendAlpha) ||
                            dual(rt.DestBlendAlpha));
}

}  // namespace

const ComputePipeline* PipelineCache::Compute(const ShaderCode& shader, std::string* error) {
  auto& slot = compute_[shader.contentId];
  if (slot) return slot.get();
  auto pipeline = std::make_unique<ComputePipeline>();
  pipeline->layout = Layout(CollectBindings({&shader}));
  VkShaderModule module = CreateModule(spirv::StripHlslDecorations(shader.words).value);
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = shader.reflection.entryPoint.c_str();
  info.layout = pipeline->layout->layout;
  VkResult result = vkCreateComputePipelines(gpu_.Device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline->pipeline);
  vkDestroyShaderModule(gpu_.Device(), module, nullptr);
  if (result != VK_SUCCESS) {
    *error = std::string("vkCreateComputePipelines failed: ") + ResultName(result);
    compute_.erase(shader.contentId);
    return nullptr;
  }
  slot = std::move(pipeline);
  return slot.get();
}

const ComputePipeline& PipelineCache::DrawAutoArgs() {
  if (drawAutoArgs_) return *drawAutoArgs_;
  drawAutoArgs_ = std::make_unique<ComputePipeline>();
  VkDescriptorSetLayoutBinding counter{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  drawAutoArgs_->layout = Layout({counter}, 2 * sizeof(uint32_t));
  std::vector<uint32_t> words(std::begin(kDrawAutoArgsSpirv), std::end(kDrawAutoArgsSpirv));
  VkShaderModule module = CreateModule(words);
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.layout = drawAutoArgs_->layout->layout;
  vkCreateComputePipelines(gpu_.Device(), VK_NULL_HANDLE, 1, &info, nullptr, &drawAutoArgs_->pipeline);
  vkDestroyShaderModule(gpu_.Device(), module, nullptr);
  return *drawAutoArgs_;
}

const GraphicsPipeline* PipelineCache::FindGraphics(const GraphicsPipelineKey& key) {
  RecentGraphics& recent = recentGraphics_[GraphicsPipelineKeyHash{}(key) % recentGraphics_.size()];
  if (recent.pipeline && recent.key == key) return recent.pipeline;
  auto it = graphics_.find(key);
  if (it == graphics_.end()) return nullptr;
  recent = {key, it->second.get()};
  return recent.pipeline;
}

const GraphicsPipeline* PipelineCache::Graphics(const GraphicsPipelineKey& key, const GraphicsPipelineInputs& inputs,
                                                std::string* error) {
  auto it = graphics_.find(key);
  if (it != graphics_.end()) return it->second.get();
  std::unique_ptr<GraphicsPipeline> pipeline = BuildGraphics(inputs, error);
  if (!pipeline) return nullptr;
  return graphics_.emplace(key, std::move(pipeline)).first->second.get();
}

std::unique_ptr<GraphicsPipeline> PipelineCache::BuildGraphics(const GraphicsPipelineInputs& in, std::string* error) {
  const GpuCapabilities& caps = gpu_.Caps();
  // Stages in pipeline order: VS, HS, DS, GS, PS.
  std::array<const ShaderCode*, 5> stages = in.shaders;
  auto pipeline = std::make_unique<GraphicsPipeline>();
  // VS-only stream output: the "geometry shader" carries the vertex shader with
  // the transform feedback decorations; it replaces the bound VS.
  if (stages[3] && stages[3]->stage == ShaderStage::Vertex) {
    stages[0] = stages[3];
    stages[3] = nullptr;
  }
  const ShaderCode* vs = stages[0];
  for (const ShaderCode* shader : stages)
    if (shader && shader->streamOutput) pipeline->streamOutput = shader->streamOutput;
  const bool tessellation = stages[1] && stages[2];
  if ((stages[1] != nullptr) != (stages[2] != nullptr)) {
    *error = "a hull shader needs a domain shader and the reverse";
    return nullptr;
  }
  if (tessellation != (in.topology >= PRIMITIVE_TOPOLOGY_1_CONTROL_POINT_PATCHLIST)) {
    *error = "tessellation shaders need a patch-list topology, and patch lists need tessellation shaders";
    return nullptr;
  }

  // Per-pipeline SPIR-V: link by semantic, then the point-size and dual-source patches.
  std::array<std::vector<uint32_t>, 5> words;
  const spirv::Reflection* producer = nullptr;
  for (size_t i = 0; i < stages.size(); ++i) {
    if (!stages[i]) continue;
    words[i] = producer ? LinkInputs(*producer, *stages[i], stages[i]->words) : stages[i]->words;
    producer = &stages[i]->reflection;
  }
  size_t lastGeometryStage = stages[3] ? 3 : tessellation ? 2 : 0;
  const bool drawsPoints = stages[3] ? stages[3]->reflection.gsOutput == spirv::GsOutputPrimitive::Points
                                     : !tessellation && in.topology == PRIMITIVE_TOPOLOGY_POINTLIST;
  if (drawsPoints) words[lastGeometryStage] = spirv::AddPointSizeOutput(words[lastGeometryStage]).value;
  const bool dualSource = UsesDualSource(*in.blend);
  if (dualSource && stages[4]) words[4] = MakeDualSourceOutput(words[4]);

  // D3D11 rasterizes nothing when no pixel shader and no depth test would use
  // it, when stream output rasterizes no stream, or when nothing writes a position.
  const DEPTH_STENCIL_DESC& ds = *in.depthStencil;
  const bool depthUsed = in.depthFormat != VK_FORMAT_UNDEFINED && (ds.DepthEnable || ds.StencilEnable);
  pipeline->rasterizes = (stages[4] || depthUsed) && stages[lastGeometryStage]->reflection.writesPosition &&
                         !(pipeline->streamOutput && pipeline->streamOutput->rasterizedStream == SO_NO_RASTERIZED_STREAM);

  // Vertex input, matched to the VS by semantic.
  std::vector<states::ShaderInput> shaderInputs;
  for (const auto& input : vs->reflection.inputs)
    if (input.location && !input.builtIn) shaderInputs.push_back({input.semanticName, input.semanticIndex, *input.location});
  states::VertexInputVk vertexInput;
  if (in.inputLayout) {
    const auto& elements = in.inputLayout->elements();
    std::array<UINT, IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT> strides{};
    vertexInput = states::BuildVertexInput(elements.data(), static_cast<UINT>(elements.size()), shaderInputs, strides);
    if (!vertexInput.error.empty()) {
      *error = vertexInput.error;
      return nullptr;
    }
    if (vertexInput.needsDivisorExt && !caps.vertexAttributeDivisor) {
      *error = "InstanceDataStepRate > 1 needs VK_EXT_vertex_attribute_divisor, which " + gpu_.AdapterName() + " lacks";
      return nullptr;
    }
    for (const auto& binding : vertexInput.bindings) pipeline->vertexSlots |= 1u << binding.binding;
  } else if (!shaderInputs.empty()) {
    *error = "the vertex shader reads " + shaderInputs[0].semanticName + " but no input layout is bound";
    return nullptr;
  }
  VkPipelineVertexInputDivisorStateCreateInfoEXT divisors{
      VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_DIVISOR_STATE_CREATE_INFO_EXT};
  divisors.vertexBindingDivisorCount = static_cast<uint32_t>(vertexInput.divisors.size());
  divisors.pVertexBindingDivisors = vertexInput.divisors.data();
  VkPipelineVertexInputStateCreateInfo vertexState{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vertexState.pNext = vertexInput.divisors.empty() ? nullptr : &divisors;
  vertexState.vertexBindingDescriptionCount = static_cast<uint32_t>(vertexInput.bindings.size());
  vertexState.pVertexBindingDescriptions = vertexInput.bindings.data();
  vertexState.vertexAttributeDescriptionCount = static_cast<uint32_t>(vertexInput.attributes.size());
  vertexState.pVertexAttributeDescriptions = vertexInput.attributes.data();

  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = tessellation ? VK_PRIMITIVE_TOPOLOGY_PATCH_LIST
                      : in.topology == PRIMITIVE_TOPOLOGY_POINTLIST ? VK_PRIMITIVE_TOPOLOGY_POINT_LIST
                      : in.topology == PRIMITIVE_TOPOLOGY_LINELIST || in.topology == PRIMITIVE_TOPOLOGY_LINESTRIP ||
                              in.topology == PRIMITIVE_TOPOLOGY_LINELIST_ADJ ||
                              in.topology == PRIMITIVE_TOPOLOGY_LINESTRIP_ADJ
                          ? VK_PRIMITIVE_TOPOLOGY_LINE_LIST
                          : VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineTessellationStateCreateInfo tessellationState{VK_STRUCTURE_TYPE_PIPELINE_TESSELLATION_STATE_CREATE_INFO};
  tessellationState.patchControlPoints = tessellation ? in.topology - PRIMITIVE_TOPOLOGY_1_CONTROL_POINT_PATCHLIST + 1 : 0;

  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};

  states::RasterizerVk raster = states::ToVulkan(*in.rasterizer, caps.depthClipEnable);
  raster.info.rasterizerDiscardEnable = !pipeline->rasterizes;
  if (raster.usesDepthClipExt) raster.info.pNext = &raster.depthClip;
  VkPipelineRasterizationStateStreamCreateInfoEXT rasterStream{
      VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_STREAM_CREATE_INFO_EXT};
  if (pipeline->streamOutput && pipeline->rasterizes && pipeline->streamOutput->rasterizedStream > 0) {
    rasterStream.rasterizationStream = pipeline->streamOutput->rasterizedStream;
    rasterStream.pNext = raster.info.pNext;
    raster.info.pNext = &rasterStream;
  }

  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = static_cast<VkSampleCountFlagBits>(in.samples);
  const VkSampleMask sampleMask = in.sampleMask;
  multisample.pSampleMask = &sampleMask;
  states::BlendVk blend = states::ToVulkan(*in.blend);
  multisample.alphaToCoverageEnable = blend.alphaToCoverageEnable;

  // Colour attachments up to the last bound one; unbound and integer targets do not blend.
  std::array<VkFormat, SIMULTANEOUS_RENDER_TARGET_COUNT> colorFormats{};
  uint32_t colorCount = 0;
  for (uint32_t i = 0; i < SIMULTANEOUS_RENDER_TARGET_COUNT; ++i) {
    const auto* format = states::GetFormatInfo(in.colorFormats[i]);
    VkPipelineColorBlendAttachmentState& attachment = blend.attachments[i];
    if (!format) {
      attachment.blendEnable = VK_FALSE;
      attachment.colorWriteMask = 0;
      continue;
    }
    colorFormats[i] = format->vkFormat;
    colorCount = i + 1;
    if (format->kind == states::ComponentKind::Uint || format->kind == states::ComponentKind::Sint)
      attachment.blendEnable = VK_FALSE;
    // (The format is asked only when the target blends.)
    const bool formatBlends = !attachment.blendEnable ||
                              gpu_.IsFormatSupported(format->vkFormat, VK_FORMAT_FEATURE_2_COLOR_ATTACHMENT_BLEND_BIT);
    if (std::string reason = states::CheckBlendable(i, format->name, attachment, formatBlends, gpu_.AdapterName());
        !reason.empty()) {
      *error = reason;
      return nullptr;
    }
    if (format->alphaIsOne) states::AdjustForMissingAlpha(attachment);
  }
  VkPipelineColorBlendStateCreateInfo colorBlend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  colorBlend.attachmentCount = colorCount;
  colorBlend.pAttachments = blend.attachments.data();

  VkPipelineDepthStencilStateCreateInfo depthStencil = states::ToVulkan(ds);
  const VkFormat vkDepthFormat = in.depthFormat;
  const bool hasStencil = vkDepthFormat == VK_FORMAT_D24_UNORM_S8_UINT ||
                          vkDepthFormat == VK_FORMAT_D32_SFLOAT_S8_UINT || vkDepthFormat == VK_FORMAT_D16_UNORM_S8_UINT;
  if (vkDepthFormat == VK_FORMAT_UNDEFINED) {
    // D3D11: with no depth-stencil view bound, the depth and stencil tests pass.
    depthStencil.depthTestEnable = depthStencil.depthWriteEnable = VK_FALSE;
  }
  if (!hasStencil) depthStencil.stencilTestEnable = VK_FALSE;
  // D3D11 drops the writes a read-only depth-stencil view does not allow; the tests still run.
  if (in.dsvFlags & DSV_READ_ONLY_DEPTH) depthStencil.depthWriteEnable = VK_FALSE;
  if (in.dsvFlags & DSV_READ_ONLY_STENCIL) depthStencil.front.writeMask = depthStencil.back.writeMask = 0;

  std::vector<VkDynamicState> dynamicStates = {
      VK_DYNAMIC_STATE_STENCIL_REFERENCE, VK_DYNAMIC_STATE_BLEND_CONSTANTS, VK_DYNAMIC_STATE_PRIMITIVE_TOPOLOGY,
      VK_DYNAMIC_STATE_PRIMITIVE_RESTART_ENABLE};
  // Strides come from IASetVertexBuffers, as in D3D11.
  if (!vertexInput.bindings.empty()) dynamicStates.push_back(VK_DYNAMIC_STATE_VERTEX_INPUT_BINDING_STRIDE);
  if (pipeline->rasterizes) {
    dynamicStates.push_back(VK_DYNAMIC_STATE_VIEWPORT_WITH_COUNT);
    dynamicStates.push_back(VK_DYNAMIC_STATE_SCISSOR_WITH_COUNT);
  }
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = static_cast<uint32_t>(dynamicStates.size());
  dynamic.pDynamicStates = dynamicStates.data();

  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = colorCount;
  rendering.pColorAttachmentFormats = colorFormats.data();
  rendering.depthAttachmentFormat = vkDepthFormat;
  rendering.stencilAttachmentFormat = hasStencil ? vkDepthFormat : VK_FORMAT_UNDEFINED;

  pipeline->layout = Layout(CollectBindings({stages[0], stages[1], stages[2], stages[3], stages[4]}));
  // The pixel shader's GetRenderTargetSamplePosition (effects/hlsl) reads the
  // sample count from this constant; shaders that declare none ignore it.
  const uint32_t sampleCount = in.samples;
  const VkSpecializationMapEntry sampleCountEntry{kRenderTargetSampleCountSpecId, 0, sizeof sampleCount};
  const VkSpecializationInfo pixelSpecialization{1, &sampleCountEntry, sizeof sampleCount, &sampleCount};
  std::vector<VkPipelineShaderStageCreateInfo> stageInfos;
  std::vector<VkShaderModule> modules;
  for (size_t i = 0; i < stages.size(); ++i) {
    if (!stages[i]) continue;
    modules.push_back(CreateModule(spirv::StripHlslDecorations(words[i]).value));
    VkPipelineShaderStageCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage = VkStage(static_cast<ShaderStage>(i));
    info.module = modules.back();
    info.pName = stages[i]->reflection.entryPoint.c_str();
    if (info.stage == VK_SHADER_STAGE_FRAGMENT_BIT) info.pSpecializationInfo = &pixelSpecialization;
    stageInfos.push_back(info);
  }

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.pNext = &rendering;
  info.stageCount = static_cast<uint32_t>(stageInfos.size());
  info.pStages = stageInfos.data();
  info.pVertexInputState = &vertexState;
  info.pInputAssemblyState = &assembly;
  info.pTessellationState = tessellation ? &tessellationState : nullptr;
  info.pViewportState = pipeline->rasterizes ? &viewport : nullptr;
  info.pRasterizationState = &raster.info;
  info.pMultisampleState = pipeline->rasterizes ? &multisample : nullptr;
  info.pDepthStencilState = pipeline->rasterizes ? &depthStencil : nullptr;
  info.pColorBlendState = pipeline->rasterizes ? &colorBlend : nullptr;
  info.pDynamicState = &dynamic;
  info.layout = pipeline->layout->layout;
  VkResult result = vkCreateGraphicsPipelines(gpu_.Device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline->pipeline);
  for (VkShaderModule module : modules) vkDestroyShaderModule(gpu_.Device(), module, nullptr);
  if (result != VK_SUCCESS) {
    *error = std::string("vkCreateGraphicsPipelines failed: ") + ResultName(result);
    return nullptr;
  }
  return pipeline;
}

}  // namespace rhi::vk
