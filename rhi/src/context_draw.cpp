// The draw and dispatch path: pipeline lookup, resource tracking, rendering
// instances, dynamic state, push descriptors.
#include <algorithm>
#include <bit>

#include "call_limits.h"
#include "context.h"
#include "pipelines.h"
#include "queries.h"
#include "resources.h"
#include "shaders.h"
#include "state_objects.h"
#include "states/formats.h"
#include "states/sampler.h"
#include "views.h"

namespace rhi::vk {

namespace {

constexpr std::array<ShaderStage, 5> kGraphicsStages = {ShaderStage::Vertex, ShaderStage::Hull, ShaderStage::Domain,
                                                        ShaderStage::Geometry, ShaderStage::Pixel};

VkPipelineStageFlags2 StageFlags(ShaderStage stage) {
  switch (stage) {
    case ShaderStage::Vertex: return VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT;
    case ShaderStage::Hull: return VK_PIPELINE_STAGE_2_TESSELLATION_CONTROL_SHADER_BIT;
    case ShaderStage::Domain: return VK_PIPELINE_STAGE_2_TESSELLATION_EVALUATION_SHADER_BIT;
    case ShaderStage::Geometry: return VK_PIPELINE_STAGE_2_GEOMETRY_SHADER_BIT;
    case ShaderStage::Pixel: return VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    case ShaderStage::Compute: return VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  }
  return VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
}

VkPrimitiveTopology ToVkTopology(PRIMITIVE_TOPOLOGY topology) {
  switch (topology) {
    case PRIMITIVE_TOPOLOGY_POINTLIST: return VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
    case PRIMITIVE_TOPOLOGY_LINELIST: return VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
    case PRIMITIVE_TOPOLOGY_LINESTRIP: return VK_PRIMITIVE_TOPOLOGY_LINE_STRIP;
    case PRIMITIVE_TOPOLOGY_TRIANGLELIST: return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    case PRIMITIVE_TOPOLOGY_TRIANGLESTRIP: return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
    case PRIMITIVE_TOPOLOGY_LINELIST_ADJ: return VK_PRIMITIVE_TOPOLOGY_LINE_LIST_WITH_ADJACENCY;
    case PRIMITIVE_TOPOLOGY_LINESTRIP_ADJ: return VK_PRIMITIVE_TOPOLOGY_LINE_STRIP_WITH_ADJACENCY;
    case PRIMITIVE_TOPOLOGY_TRIANGLELIST_ADJ: return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST_WITH_ADJACENCY;
    case PRIMITIVE_TOPOLOGY_TRIANGLESTRIP_ADJ: return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP_WITH_ADJACENCY;
    default: return VK_PRIMITIVE_TOPOLOGY_PATCH_LIST;
  }
}

bool IsStrip(PRIMITIVE_TOPOLOGY topology) {
  return topology == PRIMITIVE_TOPOLOGY_LINESTRIP || topology == PRIMITIVE_TOPOLOGY_TRIANGLESTRIP ||
         topology == PRIMITIVE_TOPOLOGY_LINESTRIP_ADJ || topology == PRIMITIVE_TOPOLOGY_TRIANGLESTRIP_ADJ;
}

}  // namespace

// ---------------------------------------------------------------------------
// Rendering instances

void ContextImpl::EndRendering() {
  if (!rendering_) return;
  vkCmdEndRendering(Commands());
  rendering_ = false;
}

void ContextImpl::BeginRendering() {
  EndRendering();
  std::array<VkRenderingAttachmentInfo, SIMULTANEOUS_RENDER_TARGET_COUNT> colors{};
  uint32_t colorCount = 0;
  VkExtent2D extent{0, 0};
  uint32_t layers = 1;
  auto grow = [&](const TextureStorage& texture, const VkImageSubresourceRange& range) {
    VkExtent3D mip = texture.MipExtent(range.baseMipLevel);
    extent = extent.width ? VkExtent2D{std::min(extent.width, mip.width), std::min(extent.height, mip.height)}
                          : VkExtent2D{mip.width, mip.height};
    layers = std::max(layers, range.layerCount);
  };
  for (uint32_t i = 0; i < renderTargets_.size(); ++i) {
    VkRenderingAttachmentInfo& color = colors[i];
    color.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
    if (RenderTargetViewImpl* view = renderTargets_[i].Get()) {
      color.imageView = view->imageView();
      color.imageLayout = VK_IMAGE_LAYOUT_GENERAL;
      color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
      color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
      grow(view->texture(), view->range());
      colorCount = i + 1;
    }
  }
  VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  VkRenderingAttachmentInfo stencil{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  bool hasStencil = false;
  if (DepthStencilViewImpl* view = depthStencil_.Get()) {
    depth.imageView = view->imageView();
    depth.imageLayout = VK_IMAGE_LAYOUT_GENERAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    hasStencil = view->texture().aspects() & VK_IMAGE_ASPECT_STENCIL_BIT;
    stencil = depth;
    // A read-only aspect is not stored: the instance writes nothing there, so
    // shaders may sample it while it is depth- or stencil-tested.
    const VkImageAspectFlags written = WrittenAspects(*view);
    depth.storeOp = written & VK_IMAGE_ASPECT_DEPTH_BIT ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_NONE;
    stencil.storeOp =
        written & VK_IMAGE_ASPECT_STENCIL_BIT ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_NONE;
    grow(view->texture(), view->range());
  }
  if (extent.width == 0) {
    // No attachments (a stream-output pass): the viewport bounds what is rasterized.
    extent = {1, 1};
    for (const VIEWPORT& vp : viewports_)
      extent = {std::max(extent.width, static_cast<uint32_t>(vp.TopLeftX + vp.Width)),
                std::max(extent.height, static_cast<uint32_t>(vp.TopLeftY + vp.Height))};
  }
  VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
  info.renderArea = {{0, 0}, extent};
  info.layerCount = layers;
  info.colorAttachmentCount = colorCount;
  info.pColorAttachments = colors.data();
  info.pDepthAttachment = depthStencil_ ? &depth : nullptr;
  info.pStencilAttachment = hasStencil ? &stencil : nullptr;
  vkCmdBeginRendering(Commands(), &info);
  rendering_ = true;
  renderTargetsChanged_ = false;
  if (renderArea_.width != extent.width || renderArea_.height != extent.height) dynamicDirty_.viewport = true;
  renderArea_ = extent;
}

// ---------------------------------------------------------------------------
// Draw preparation

const GraphicsPipeline* ContextImpl::PrepareDraw(const char* call, TrackedResource* indirect,
                                                 const Access& indirectUse) {
  if (predicationSkips_) return nullptr;  // SetPredication
  if (!stages_[0].shader) {
    ReportDrawError(std::string(call) + ": no vertex shader is bound; the draw is skipped");
    return nullptr;
  }
  const GraphicsPipeline* pipeline = currentPipeline_ ? currentPipeline_ : LookUpPipeline(call);
  if (!pipeline) return nullptr;
  currentPipeline_ = pipeline;
  TrackDrawResources(call, *pipeline, indirect, indirectUse);
  BindGraphicsState(*pipeline);
  return pipeline;
}

const GraphicsPipeline* ContextImpl::LookUpPipeline(const char* call) {
  PipelineCache& cache = device_->pipelines();
  if (const GraphicsPipeline* pipeline = cache.FindGraphics(pipelineKey_)) return pipeline;
  // A new combination: gather what the pipeline is built from.
  GraphicsPipelineInputs inputs;
  for (size_t i = 0; i < kGraphicsStages.size(); ++i) inputs.shaders[i] = stages_[static_cast<uint32_t>(kGraphicsStages[i])].shader;
  inputs.inputLayout = inputLayout_.Get();
  inputs.blend = &BlendDescOf(blendState_.Get());
  inputs.depthStencil = &DepthStencilDescOf(depthStencilState_.Get());
  inputs.rasterizer = &RasterizerDescOf(rasterizer_.Get());
  for (uint32_t i = 0; i < renderTargets_.size(); ++i)
    inputs.colorFormats[i] = static_cast<DXGI_FORMAT>(pipelineKey_.colorFormats[i]);
  inputs.depthFormat = static_cast<VkFormat>(pipelineKey_.depthFormat);
  inputs.dsvFlags = pipelineKey_.dsvFlags;
  inputs.samples = pipelineKey_.samples;
  inputs.sampleMask = sampleMask_;
  inputs.topology = topology_;
  std::string error;
  const GraphicsPipeline* pipeline = cache.Graphics(pipelineKey_, inputs, &error);
  if (!pipeline) ReportDrawError(std::string(call) + ": " + error + "; the draw is skipped");
  return pipeline;
}

void ContextImpl::TrackDrawResources(const char* call, const GraphicsPipeline& pipeline, TrackedResource* indirect,
                                     const Access& indirectUse) {
  for (uint32_t slots = pipeline.vertexSlots; slots; slots &= slots - 1)
    if (BufferImpl* buffer = vertexBuffers_[std::countr_zero(slots)].buffer.Get()) Use(*buffer, uses::kVertexBuffer);
  if (indexBuffer_.buffer) Use(*indexBuffer_.buffer, uses::kIndexBuffer);
  if (indirect) Use(*indirect, indirectUse);
  for (const RegisterSlot& reg : pipeline.layout->registers) {
    const StageState& stage = stages_[static_cast<uint32_t>(reg.stage)];
    const VkPipelineStageFlags2 stageFlags = StageFlags(reg.stage);
    if (reg.registerClass == RegisterClass::ConstantBuffer && reg.slot < stage.constantBuffers.size()) {
      if (BufferImpl* cb = stage.constantBuffers[reg.slot].Get())
        Use(*cb, {stageFlags, VK_ACCESS_2_UNIFORM_READ_BIT, false});
    } else if (reg.registerClass == RegisterClass::ShaderResource && reg.slot < stage.shaderResources.size()) {
      if (ShaderResourceViewImpl* view = stage.shaderResources[reg.slot].Get())
        Use(view->tracked(), {stageFlags, VK_ACCESS_2_SHADER_READ_BIT, false});
    } else if (reg.registerClass == RegisterClass::UnorderedAccess) {
      UseUav(call, reg, stageFlags);
    }
  }
  if (pipeline.streamOutput) PrepareStreamOutTargets();
  // Attachments: writes within one rendering instance need no barrier, so
  // they are tracked against the instance they will be drawn in.
  const bool restart = !rendering_ || renderTargetsChanged_ || pendingBarrier_.dstStageMask != 0;
  const uint64_t instance = restart ? renderingInstance_ + 1 : renderingInstance_;
  for (auto& view : renderTargets_)
    if (view) Use(view->texture(), uses::kColorAttachment, instance);
  if (depthStencil_) {
    const bool writes = WrittenAspects(*depthStencil_) != 0;
    Use(depthStencil_->texture(), writes ? uses::kDepthAttachment : uses::kDepthAttachmentRead, writes ? instance : 0);
  }
  FlushBarriers();
  if (restart) {
    ++renderingInstance_;
    BeginRendering();
  }
}

// D3D11 orders UAV accesses of one draw or dispatch after those of the
// previous ones: every use is a write, so the next use waits for it (and a
// draw after a UAV-writing draw starts a new rendering instance for the barrier).
void ContextImpl::UseUav(const char* call, const RegisterSlot& reg, VkPipelineStageFlags2 stages) {
  if (reg.slot >= PS_CS_UAV_REGISTER_COUNT) return;
  UnorderedAccessViewImpl* view = UavsOf(reg.stage)[reg.slot].Get();
  if (!view) return;
  const Access use{stages, VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_SHADER_WRITE_BIT, true};
  if (!reg.counter) {
    Use(view->tracked(), use);
  } else if (BufferImpl* counter = view->counter()) {
    Use(*counter, use);
  } else {
    // As the D3D11 debug layer, report and draw: the counter reads 0 and its updates are lost.
    ReportDrawError(std::string(call) + ": the shader uses the hidden counter of UAV u" + std::to_string(reg.slot) +
                    " (Append, Consume, IncrementCounter, DecrementCounter), but that view was created without "
                    "BUFFER_UAV_FLAG_APPEND or BUFFER_UAV_FLAG_COUNTER");
  }
}

void ContextImpl::BindGraphicsState(const GraphicsPipeline& pipeline) {
  VkCommandBuffer commands = Commands();
  if (boundPipeline_ != &pipeline) {
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.pipeline);
    // A pipeline without viewport state invalidates it; pushed descriptors
    // survive only binds with the same layout; the vertex stride state exists
    // only in pipelines with vertex bindings.
    if (pipeline.rasterizes && !(boundPipeline_ && boundPipeline_->rasterizes)) dynamicDirty_.viewport = true;
    if (!boundPipeline_ || boundPipeline_->layout != pipeline.layout) descriptorsDirty_ = true;
    if (!boundPipeline_ || boundPipeline_->vertexSlots != pipeline.vertexSlots) vertexBuffersDirty_ = true;
    boundPipeline_ = &pipeline;
  }
  if (dynamicDirty_.viewport && pipeline.rasterizes) {
    SetViewportsAndScissors();
    dynamicDirty_.viewport = false;
  }
  if (dynamicDirty_.stencilRef) vkCmdSetStencilReference(commands, VK_STENCIL_FACE_FRONT_AND_BACK, stencilRef_ & 0xFF);
  if (dynamicDirty_.blendConstants) vkCmdSetBlendConstants(commands, blendFactor_.data());
  if (dynamicDirty_.topology) {
    vkCmdSetPrimitiveTopology(commands, ToVkTopology(topology_));
    vkCmdSetPrimitiveRestartEnable(commands, IsStrip(topology_));
  }
  dynamicDirty_.stencilRef = dynamicDirty_.blendConstants = dynamicDirty_.topology = false;
  if (vertexBuffersDirty_) {
    BindVertexAndIndexBuffers(pipeline);
    vertexBuffersDirty_ = false;
  }
  if (descriptorsDirty_ && !pipeline.layout->bindings.empty()) {
    PushDescriptors(VK_PIPELINE_BIND_POINT_GRAPHICS, *pipeline.layout);
  }
  descriptorsDirty_ = false;
}

void ContextImpl::SetViewportsAndScissors() {
  VkCommandBuffer commands = Commands();
  std::vector<VkViewport> viewports;
  for (const VIEWPORT& vp : viewports_) {
    // A negative height flips Vulkan's y so clip space matches D3D11 (y up, origin top-left).
    viewports.push_back({vp.TopLeftX, vp.TopLeftY + vp.Height, vp.Width, -vp.Height, vp.MinDepth, vp.MaxDepth});
  }
  if (viewports.empty()) {
    // D3D11 rasterizes nothing without a viewport; a zero-area one does the same.
    viewports.push_back({0, 0, 1, 0, 0, 1});
  }
  vkCmdSetViewportWithCount(commands, static_cast<uint32_t>(viewports.size()), viewports.data());
  std::vector<VkRect2D> scissors;
  const bool scissorEnable = RasterizerDescOf(rasterizer_.Get()).ScissorEnable;
  for (size_t i = 0; i < viewports.size(); ++i) {
    if (scissorEnable) {
      RECT r = i < scissors_.size() ? scissors_[i] : RECT{0, 0, 0, 0};
      int32_t x = std::max(r.left, 0), y = std::max(r.top, 0);
      scissors.push_back({{x, y},
                          {static_cast<uint32_t>(std::max(r.right - x, 0)),
                           static_cast<uint32_t>(std::max(r.bottom - y, 0))}});
    } else {
      scissors.push_back({{0, 0}, renderArea_});
    }
  }
  vkCmdSetScissorWithCount(commands, static_cast<uint32_t>(scissors.size()), scissors.data());
}

void ContextImpl::BindVertexAndIndexBuffers(const GraphicsPipeline& pipeline) {
  VkCommandBuffer commands = Commands();
  for (uint32_t slots = pipeline.vertexSlots; slots; slots &= slots - 1) {
    const uint32_t slot = static_cast<uint32_t>(std::countr_zero(slots));
    const VertexBufferBinding& binding = vertexBuffers_[slot];
    VkBuffer buffer = binding.buffer ? binding.buffer->handle() : VK_NULL_HANDLE;
    VkDeviceSize offset = binding.buffer ? binding.buffer->baseOffset() + binding.offset : 0;
    VkDeviceSize stride = binding.stride;
    vkCmdBindVertexBuffers2(commands, slot, 1, &buffer, &offset, nullptr, &stride);
  }
  if (indexBuffer_.buffer) {
    vkCmdBindIndexBuffer(commands, indexBuffer_.buffer->handle(),
                         indexBuffer_.buffer->baseOffset() + indexBuffer_.offset,
                         indexBuffer_.format == DXGI_FORMAT_R16_UINT ? VK_INDEX_TYPE_UINT16 : VK_INDEX_TYPE_UINT32);
  }
}

void ContextImpl::PushDescriptors(VkPipelineBindPoint bindPoint, const PipelineLayout& layout) {
  // Scratch arrays keep their capacity across draws: no allocation per draw.
  auto& [writes, buffers, images, texelBuffers] = descriptorScratch_;
  const size_t count = layout.bindings.size();
  writes.resize(count);
  buffers.resize(count);
  images.resize(count);
  texelBuffers.resize(count);
  for (size_t i = 0; i < count; ++i) {
    const VkDescriptorSetLayoutBinding& binding = layout.bindings[i];
    const RegisterSlot& reg = layout.registers[i];
    const StageState& stage = stages_[static_cast<uint32_t>(reg.stage)];
    VkWriteDescriptorSet& write = writes[i];
    write = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstBinding = binding.binding;
    write.descriptorCount = 1;
    write.descriptorType = binding.descriptorType;
    // Only the array the type reads: lavapipe copies every non-null one per push.
    switch (reg.registerClass) {
      case RegisterClass::ConstantBuffer: {
        write.pBufferInfo = &buffers[i];
        BufferImpl* cb = reg.slot < stage.constantBuffers.size() ? stage.constantBuffers[reg.slot].Get() : nullptr;
        buffers[i] = cb ? VkDescriptorBufferInfo{cb->handle(), cb->baseOffset(), cb->desc().ByteWidth}
                        : VkDescriptorBufferInfo{VK_NULL_HANDLE, 0, VK_WHOLE_SIZE};
        continue;
      }
      case RegisterClass::Sampler: {
        write.pImageInfo = &images[i];
        SamplerStateImpl* sampler = reg.slot < stage.samplers.size() ? stage.samplers[reg.slot].Get() : nullptr;
        // D3D11 samples with the default sampler state where none is bound.
        images[i] = {sampler ? sampler->handle() : defaultSampler(), VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL};
        continue;
      }
      case RegisterClass::ShaderResource:
      case RegisterClass::UnorderedAccess:
        WriteViewDescriptor(i, reg, stage);
        continue;
    }
  }
  device_->gpu().vkCmdPushDescriptorSetKHR(Commands(), bindPoint, layout.layout, 0, static_cast<uint32_t>(count),
                                           writes.data());
}

// Entry i of the descriptor scratch for a shader-resource or unordered-access
// binding (its write's type already set): a buffer, texel-buffer or image
// descriptor, or a null one (robustness2) where nothing is bound: reads return
// zero, as in D3D11.
void ContextImpl::WriteViewDescriptor(size_t i, const RegisterSlot& reg, const StageState& stage) {
  auto& [writes, buffers, images, texelBuffers] = descriptorScratch_;
  VkWriteDescriptorSet& write = writes[i];
  ViewTarget* view = nullptr;
  if (reg.registerClass == RegisterClass::ShaderResource) {
    if (reg.slot < stage.shaderResources.size()) view = stage.shaderResources[reg.slot].Get();
  } else if (reg.slot < PS_CS_UAV_REGISTER_COUNT) {
    UnorderedAccessViewImpl* uav = UavsOf(reg.stage)[reg.slot].Get();
    if (reg.counter) {
      // The UAV's hidden counter; a UAV without one binds a null buffer.
      const BufferImpl* counter = uav ? uav->counter() : nullptr;
      write.pBufferInfo = &buffers[i];
      buffers[i] = counter ? VkDescriptorBufferInfo{counter->handle(), counter->baseOffset(), sizeof(UINT)}
                           : VkDescriptorBufferInfo{VK_NULL_HANDLE, 0, VK_WHOLE_SIZE};
      return;
    }
    view = uav;
  }
  const ViewTarget* bufferView = view && view->buffer() ? view : nullptr;
  switch (write.descriptorType) {
    case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
    case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
      write.pBufferInfo = &buffers[i];
      buffers[i] = bufferView ? bufferView->bufferRange() : VkDescriptorBufferInfo{VK_NULL_HANDLE, 0, VK_WHOLE_SIZE};
      break;
    case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER:
    case VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER:
      write.pTexelBufferView = &texelBuffers[i];
      texelBuffers[i] = bufferView ? bufferView->bufferView() : VK_NULL_HANDLE;
      break;
    default:
      write.pImageInfo = &images[i];
      // Shader-resource views follow their texture's minimum LOD (SetResourceMinLOD).
      images[i] = {VK_NULL_HANDLE, !view ? VK_NULL_HANDLE
                                         : reg.registerClass == RegisterClass::ShaderResource
                                               ? view->SampledImageView()
                                               : view->imageView(),
                   VK_IMAGE_LAYOUT_GENERAL};
      break;
  }
}

VkSampler ContextImpl::defaultSampler() {
  if (!defaultSampler_) {
    // D3D11 samples unbound sampler slots with the default sampler state.
    states::SamplerVk sampler = states::ToVulkan(SAMPLER_DESC{});
    vkCreateSampler(device_->gpu().Device(), &sampler.info, nullptr, &defaultSampler_);
  }
  return defaultSampler_;
}

// ---------------------------------------------------------------------------
// Draws

void ContextImpl::Draw(UINT VertexCount, UINT StartVertexLocation) {
  DrawInstanced(VertexCount, 1, StartVertexLocation, 0);
}

void ContextImpl::DrawIndexed(UINT IndexCount, UINT StartIndexLocation, INT BaseVertexLocation) {
  DrawIndexedInstanced(IndexCount, 1, StartIndexLocation, BaseVertexLocation, 0);
}

void ContextImpl::DrawInstanced(UINT VertexCountPerInstance, UINT InstanceCount, UINT StartVertexLocation,
                                UINT StartInstanceLocation) {
  const GraphicsPipeline* pipeline = PrepareDraw("Draw");
  if (!pipeline) return;
  BeginStreamOut(*pipeline);
  vkCmdDraw(Commands(), VertexCountPerInstance, InstanceCount, StartVertexLocation, StartInstanceLocation);
  EndStreamOut(*pipeline);
}

void ContextImpl::DrawIndexedInstanced(UINT IndexCountPerInstance, UINT InstanceCount, UINT StartIndexLocation,
                                       INT BaseVertexLocation, UINT StartInstanceLocation) {
  if (!indexBuffer_.buffer) {
    ReportDrawError("DrawIndexed: no index buffer is bound; the draw is skipped");
    return;
  }
  const GraphicsPipeline* pipeline = PrepareDraw("DrawIndexed");
  if (!pipeline) return;
  BeginStreamOut(*pipeline);
  vkCmdDrawIndexed(Commands(), IndexCountPerInstance, InstanceCount, StartIndexLocation, BaseVertexLocation,
                   StartInstanceLocation);
  EndStreamOut(*pipeline);
}

void ContextImpl::DrawInstancedIndirect(Buffer* pBufferForArgs, UINT AlignedByteOffsetForArgs) {
  auto* args = static_cast<BufferImpl*>(pBufferForArgs);
  if (!args || !(args->desc().MiscFlags & RESOURCE_MISC_DRAWINDIRECT_ARGS) || AlignedByteOffsetForArgs % 4) {
    ReportDrawError("DrawInstancedIndirect: needs a RESOURCE_MISC_DRAWINDIRECT_ARGS buffer and a 4-byte aligned offset");
    return;
  }
  const GraphicsPipeline* pipeline = PrepareDraw("DrawInstancedIndirect", args);
  if (!pipeline) return;
  BeginStreamOut(*pipeline);
  vkCmdDrawIndirect(Commands(), args->handle(), args->baseOffset() + AlignedByteOffsetForArgs, 1, 0);
  EndStreamOut(*pipeline);
}

void ContextImpl::DrawIndexedInstancedIndirect(Buffer* pBufferForArgs, UINT AlignedByteOffsetForArgs) {
  auto* args = static_cast<BufferImpl*>(pBufferForArgs);
  if (!args || !(args->desc().MiscFlags & RESOURCE_MISC_DRAWINDIRECT_ARGS) || AlignedByteOffsetForArgs % 4) {
    ReportDrawError(
        "DrawIndexedInstancedIndirect: needs a RESOURCE_MISC_DRAWINDIRECT_ARGS buffer and a 4-byte aligned offset");
    return;
  }
  if (!indexBuffer_.buffer) {
    ReportDrawError("DrawIndexedInstancedIndirect: no index buffer is bound; the draw is skipped");
    return;
  }
  const GraphicsPipeline* pipeline = PrepareDraw("DrawIndexedInstancedIndirect", args);
  if (!pipeline) return;
  BeginStreamOut(*pipeline);
  vkCmdDrawIndexedIndirect(Commands(), args->handle(), args->baseOffset() + AlignedByteOffsetForArgs, 1, 0);
  EndStreamOut(*pipeline);
}

// ---------------------------------------------------------------------------
// Compute

const ComputePipeline* ContextImpl::PrepareDispatch(const char* call) {
  if (predicationSkips_) return nullptr;  // SetPredication
  const ShaderCode* shader = stages_[static_cast<uint32_t>(ShaderStage::Compute)].shader;
  if (!shader) {
    ReportDrawError(std::string(call) + ": no compute shader is bound; the dispatch is skipped");
    return nullptr;
  }
  std::string error;
  const ComputePipeline* pipeline = device_->pipelines().Compute(*shader, &error);
  if (!pipeline) {
    ReportDrawError(std::string(call) + ": " + error);
    return nullptr;
  }
  EndRendering();
  const StageState& stage = stages_[static_cast<uint32_t>(ShaderStage::Compute)];
  for (const RegisterSlot& reg : pipeline->layout->registers) {
    const Access read{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_READ_BIT, false};
    if (reg.registerClass == RegisterClass::ConstantBuffer && reg.slot < stage.constantBuffers.size()) {
      if (BufferImpl* cb = stage.constantBuffers[reg.slot].Get())
        Use(*cb, {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_UNIFORM_READ_BIT, false});
    } else if (reg.registerClass == RegisterClass::ShaderResource && reg.slot < stage.shaderResources.size()) {
      if (ShaderResourceViewImpl* view = stage.shaderResources[reg.slot].Get()) Use(view->tracked(), read);
    } else if (reg.registerClass == RegisterClass::UnorderedAccess) {
      UseUav(call, reg, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    }
  }
  return pipeline;
}

void ContextImpl::BindCompute(const ComputePipeline& pipeline) {
  FlushBarriers();
  vkCmdBindPipeline(Commands(), VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.pipeline);
  if (!pipeline.layout->bindings.empty())
    PushDescriptors(VK_PIPELINE_BIND_POINT_COMPUTE, *pipeline.layout);
}

void ContextImpl::Dispatch(UINT ThreadGroupCountX, UINT ThreadGroupCountY, UINT ThreadGroupCountZ) {
  if (!DispatchAllowed(device_->gpu(), ThreadGroupCountX, ThreadGroupCountY, ThreadGroupCountZ)) return;
  const ComputePipeline* pipeline = PrepareDispatch("Dispatch");
  if (!pipeline) return;
  BindCompute(*pipeline);
  vkCmdDispatch(Commands(), ThreadGroupCountX, ThreadGroupCountY, ThreadGroupCountZ);
}

void ContextImpl::DispatchIndirect(Buffer* pBufferForArgs, UINT AlignedByteOffsetForArgs) {
  auto* args = static_cast<BufferImpl*>(pBufferForArgs);
  if (!args || !(args->desc().MiscFlags & RESOURCE_MISC_DRAWINDIRECT_ARGS) || AlignedByteOffsetForArgs % 4) {
    ReportDrawError("DispatchIndirect: needs a RESOURCE_MISC_DRAWINDIRECT_ARGS buffer and a 4-byte aligned offset");
    return;
  }
  const ComputePipeline* pipeline = PrepareDispatch("DispatchIndirect");
  if (!pipeline) return;
  Use(*args, uses::kIndirectArgs);
  BindCompute(*pipeline);
  vkCmdDispatchIndirect(Commands(), args->handle(), args->baseOffset() + AlignedByteOffsetForArgs);
}

}  // namespace rhi::vk
