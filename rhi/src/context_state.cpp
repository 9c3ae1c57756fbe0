// The context's binding calls: they store state, apply D3D11's binding rules,
// and mark what the next draw must re-emit.
#include <algorithm>

#include "call_limits.h"
#include "context.h"
#include "pipelines.h"
#include "queries.h"
#include "resources.h"
#include "shaders.h"
#include "spirv/reflection.h"
#include "state_objects.h"
#include "views.h"

namespace rhi::vk {

namespace {

// The D3D11 method prefix of a stage ("PS" of PSSetShaderResources).
const char* StagePrefix(ShaderStage stage) {
  constexpr const char* kPrefixes[] = {"VS", "HS", "DS", "GS", "PS", "CS"};
  return kPrefixes[static_cast<uint32_t>(stage)];
}

}  // namespace

ContextImpl::ContextImpl(DeviceImpl* device)
    : device_(device), queries_(std::make_unique<QueryTracker>(device->gpu())) {
  queries_->statistics = SupportedStatistics(device->gpu().Caps());
}

ContextImpl::~ContextImpl() {
  VkDevice vkDevice = device_->gpu().Device();
  VkSampler sampler = defaultSampler_;
  device_->gpu().DeferDestroy([=] { vkDestroySampler(vkDevice, sampler, nullptr); });
}

void ContextImpl::IASetInputLayout(InputLayout* pInputLayout) {
  auto* layout = static_cast<InputLayoutImpl*>(pInputLayout);
  if (layout == inputLayout_.Get()) return;
  inputLayout_ = layout;
  pipelineKey_.inputLayout = layout ? layout->contentId() : 0;
  PipelineStateChanged();
}

void ContextImpl::IASetVertexBuffers(UINT StartSlot, UINT NumBuffers, Buffer* const* ppVertexBuffers,
                                     const UINT* pStrides, const UINT* pOffsets) {
  if (!SlotRangeAllowed(device_->gpu(), "IASetVertexBuffers", StartSlot, NumBuffers, IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT))
    return;
  for (UINT i = 0; i < NumBuffers && StartSlot + i < vertexBuffers_.size(); ++i) {
    auto* buffer = static_cast<BufferImpl*>(ppVertexBuffers ? ppVertexBuffers[i] : nullptr);
    // A buffer bound as a stream-output target cannot be read: D3D11 binds NULL instead.
    if (buffer && IsBoundForWriting(buffer)) buffer = nullptr;
    vertexBuffers_[StartSlot + i] = {buffer, pStrides ? pStrides[i] : 0, pOffsets ? pOffsets[i] : 0};
  }
  vertexBuffersDirty_ = true;
}

void ContextImpl::IASetIndexBuffer(Buffer* pIndexBuffer, DXGI_FORMAT Format, UINT Offset) {
  auto* buffer = static_cast<BufferImpl*>(pIndexBuffer);
  if (buffer && Format != DXGI_FORMAT_R16_UINT && Format != DXGI_FORMAT_R32_UINT) {
    ReportDrawError("IASetIndexBuffer: Format must be DXGI_FORMAT_R16_UINT or DXGI_FORMAT_R32_UINT");
    buffer = nullptr;
  }
  if (buffer && IsBoundForWriting(buffer)) buffer = nullptr;
  indexBuffer_ = {buffer, Format, Offset};
  vertexBuffersDirty_ = true;
}

void ContextImpl::IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY Topology) {
  if (Topology == topology_) return;
  topology_ = Topology;
  pipelineKey_.topologyClass = TopologyClass(Topology);
  PipelineStateChanged();
  dynamicDirty_.topology = true;
}

void ContextImpl::SetShader(ShaderStage stage, Bindable* object, const ShaderCode* code) {
  StageState& state = stages_[static_cast<uint32_t>(stage)];
  if (object == state.shaderObject.Get()) return;
  state.shaderObject = object;
  state.shader = code;
  descriptorsDirty_ = true;
  if (stage == ShaderStage::Compute) return;
  // The key's shader slots are VS, HS, DS, GS, PS: the graphics stages in ShaderStage order.
  pipelineKey_.shaders[static_cast<uint32_t>(stage)] = code ? code->contentId : 0;
  PipelineStateChanged();
}

// Each interface has one implementation, so a static_cast finds the code.
#define RHI_SET_SHADER(Prefix, Stage, Interface)                                          \
  void ContextImpl::Prefix##SetShader(Interface* pShader, ClassInstance* const*, UINT) {  \
    auto* object = static_cast<ShaderObject<Interface>*>(pShader);                        \
    SetShader(ShaderStage::Stage, object, object ? object->code().get() : nullptr);       \
  }
RHI_SET_SHADER(VS, Vertex, VertexShader)
RHI_SET_SHADER(HS, Hull, HullShader)
RHI_SET_SHADER(DS, Domain, DomainShader)
RHI_SET_SHADER(GS, Geometry, GeometryShader)
RHI_SET_SHADER(PS, Pixel, PixelShader)
RHI_SET_SHADER(CS, Compute, ComputeShader)
#undef RHI_SET_SHADER

void ContextImpl::SetConstantBuffers(ShaderStage stage, UINT start, UINT count, Buffer* const* buffers) {
  if (!SlotRangeAllowed(device_->gpu(), std::string(StagePrefix(stage)) + "SetConstantBuffers", start, count,
                        COMMONSHADER_CONSTANT_BUFFER_API_SLOT_COUNT))
    return;
  auto& slots = stages_[static_cast<uint32_t>(stage)].constantBuffers;
  for (UINT i = 0; i < count && start + i < slots.size(); ++i)
    slots[start + i] = static_cast<BufferImpl*>(buffers ? buffers[i] : nullptr);
  descriptorsDirty_ = true;
}

void ContextImpl::SetShaderResources(ShaderStage stage, UINT start, UINT count,
                                     ShaderResourceView* const* views) {
  if (!SlotRangeAllowed(device_->gpu(), std::string(StagePrefix(stage)) + "SetShaderResources", start, count,
                        COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT))
    return;
  auto& slots = stages_[static_cast<uint32_t>(stage)].shaderResources;
  for (UINT i = 0; i < count && start + i < slots.size(); ++i) {
    auto* view = static_cast<ShaderResourceViewImpl*>(views ? views[i] : nullptr);
    // A resource bound for writing cannot be bound for reading: D3D11 binds NULL.
    // A depth buffer behind a read-only depth-stencil view is not being written.
    if (view && IsBoundForWriting(view->resource(), view->range().aspectMask)) {
      ReportHazard(std::string(spirv::StageName(static_cast<spirv::Stage>(stage))) +
                   "SetShaderResources: the resource of shader resource slot " + std::to_string(start + i) +
                   (IsBoundAsUav(view->resource()) ? " is bound as an unordered access view"
                                                   : " is still bound on output") +
                   "; forcing it to NULL");
      view = nullptr;
    }
    slots[start + i] = view;
  }
  descriptorsDirty_ = true;
}

void ContextImpl::SetSamplers(ShaderStage stage, UINT start, UINT count, SamplerState* const* samplers) {
  if (!SlotRangeAllowed(device_->gpu(), std::string(StagePrefix(stage)) + "SetSamplers", start, count,
                        COMMONSHADER_SAMPLER_SLOT_COUNT))
    return;
  auto& slots = stages_[static_cast<uint32_t>(stage)].samplers;
  for (UINT i = 0; i < count && start + i < slots.size(); ++i)
    slots[start + i] = static_cast<SamplerStateImpl*>(samplers ? samplers[i] : nullptr);
  descriptorsDirty_ = true;
}

void ContextImpl::CSSetUnorderedAccessViews(UINT StartSlot, UINT NumUAVs, UnorderedAccessView* const* ppUAVs,
                                            const UINT* pUAVInitialCounts) {
  if (StartSlot >= PS_CS_UAV_REGISTER_COUNT || NumUAVs > PS_CS_UAV_REGISTER_COUNT - StartSlot) {
    ReportDrawError("CSSetUnorderedAccessViews: StartSlot (" + std::to_string(StartSlot) + ") + NumUAVs (" +
                    std::to_string(NumUAVs) + ") exceeds the " + std::to_string(PS_CS_UAV_REGISTER_COUNT) +
                    " UAV slots of feature level 11_0; the call is ignored");
    return;
  }
  BindUavs(computeUavs_, StartSlot, NumUAVs, ppUAVs, pUAVInitialCounts, false, "CSSetUnorderedAccessViews");
}

void ContextImpl::BindUavs(UavSlots& slots, UINT start, UINT count, UnorderedAccessView* const* views,
                           const UINT* initialCounts, bool unbindOthers, const char* call) {
  auto viewAt = [&](UINT slot) {
    const bool inRange = slot >= start && slot - start < count;
    return static_cast<UnorderedAccessViewImpl*>(inRange && views ? views[slot - start] : nullptr);
  };
  // Unbind every new view's resource first, so that views of one resource in
  // two slots of this call both stay bound.
  for (UINT slot = start; slot < start + count; ++slot)
    if (UnorderedAccessViewImpl* view = viewAt(slot)) UnbindFromReads(view->resource(), call);
  for (UINT slot = 0; slot < slots.size(); ++slot) {
    const bool inRange = slot >= start && slot - start < count;
    if (!inRange && !unbindOthers) continue;
    UnorderedAccessViewImpl* view = viewAt(slot);
    slots[slot] = view;
    if (view && initialCounts) SetUavCounter(*view, initialCounts[slot - start]);
  }
  descriptorsDirty_ = true;
}

void ContextImpl::SetUavCounter(UnorderedAccessViewImpl& view, UINT count) {
  BufferImpl* counter = view.counter();
  if (!counter || count == UINT(-1)) return;
  // A fill is a transfer: outside rendering, after the shaders that used the count.
  EndRendering();
  Use(*counter, uses::kTransferWrite);
  FlushBarriers();
  vkCmdFillBuffer(Commands(), counter->handle(), counter->baseOffset(), sizeof(UINT), count);
}

void ContextImpl::SOSetTargets(UINT NumBuffers, Buffer* const* ppSOTargets, const UINT* pOffsets) {
  if (!CountAllowed(device_->gpu(), "SOSetTargets", "NumBuffers", NumBuffers, SO_BUFFER_SLOT_COUNT)) return;
  // D3D11: unspecified slots up to SO_BUFFER_SLOT_COUNT are unbound.
  for (UINT i = 0; i < SO_BUFFER_SLOT_COUNT; ++i) {
    auto* buffer = i < NumBuffers && ppSOTargets ? static_cast<BufferImpl*>(ppSOTargets[i]) : nullptr;
    if (buffer && !(buffer->desc().BindFlags & BIND_STREAM_OUTPUT)) {
      ReportDrawError("SOSetTargets: buffer " + std::to_string(i) + " lacks BIND_STREAM_OUTPUT; bound as NULL");
      buffer = nullptr;
    }
    if (buffer) UnbindFromReads(buffer, "SOSetTargets");
    const UINT offset = buffer && pOffsets ? pOffsets[i] : 0;
    streamOut_[i] = {buffer, offset, buffer && offset != UINT(-1)};
  }
}

void ContextImpl::SOGetTargets(UINT NumBuffers, Buffer** ppSOTargets) {
  for (UINT i = 0; i < NumBuffers && i < SO_BUFFER_SLOT_COUNT; ++i) {
    BufferImpl* buffer = streamOut_[i].buffer.Get();
    if (buffer) buffer->AddRef();
    ppSOTargets[i] = buffer;
  }
}

void ContextImpl::RSSetState(RasterizerState* pRasterizerState) {
  auto* state = static_cast<RasterizerStateImpl*>(pRasterizerState);
  if (state == rasterizer_.Get()) return;
  rasterizer_ = state;
  pipelineKey_.rasterizer = state ? state->contentId() : 0;
  PipelineStateChanged();
  dynamicDirty_.viewport = true;  // ScissorEnable decides the scissor
}

void ContextImpl::RSSetViewports(UINT NumViewports, const VIEWPORT* pViewports) {
  if (!CountAllowed(device_->gpu(), "RSSetViewports", "NumViewports", NumViewports,
                    VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE))
    return;
  viewports_.assign(pViewports, pViewports + NumViewports);
  dynamicDirty_.viewport = true;
}

void ContextImpl::RSSetScissorRects(UINT NumRects, const RECT* pRects) {
  if (!CountAllowed(device_->gpu(), "RSSetScissorRects", "NumRects", NumRects,
                    VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE))
    return;
  scissors_.assign(pRects, pRects + NumRects);
  dynamicDirty_.viewport = true;
}

// D3D11 runs OMSetRenderTargets as OMSetRenderTargetsAndUnorderedAccessViews
// with no UAVs from slot NumViews on: the pixel-shader UAVs are unbound.
void ContextImpl::OMSetRenderTargets(UINT NumViews, RenderTargetView* const* ppRenderTargetViews,
                                     DepthStencilView* pDepthStencilView) {
  SetOutputMerger("OMSetRenderTargets", NumViews, ppRenderTargetViews, pDepthStencilView, NumViews, 0, nullptr,
                  nullptr);
}

void ContextImpl::OMSetRenderTargetsAndUnorderedAccessViews(UINT NumRTVs, RenderTargetView* const* ppRenderTargetViews,
                                                            DepthStencilView* pDepthStencilView, UINT UAVStartSlot,
                                                            UINT NumUAVs,
                                                            UnorderedAccessView* const* ppUnorderedAccessViews,
                                                            const UINT* pUAVInitialCounts) {
  SetOutputMerger("OMSetRenderTargetsAndUnorderedAccessViews", NumRTVs, ppRenderTargetViews, pDepthStencilView,
                  UAVStartSlot, NumUAVs, ppUnorderedAccessViews, pUAVInitialCounts);
}

void ContextImpl::SetOutputMerger(const char* call, UINT numRtvs, RenderTargetView* const* rtvs, DepthStencilView* dsv,
                                  UINT uavStart, UINT numUavs, UnorderedAccessView* const* uavs,
                                  const UINT* initialCounts) {
  if (std::string reason = CheckOutputMergerBinding(numRtvs, rtvs, dsv, uavStart, numUavs, uavs); !reason.empty()) {
    ReportDrawError(std::string(call) + ": " + reason + "; the call is ignored");
    return;
  }
  if (numRtvs != KEEP_RENDER_TARGETS_AND_DEPTH_STENCIL) BindRenderTargets(call, numRtvs, rtvs, dsv);
  if (numUavs != KEEP_UNORDERED_ACCESS_VIEWS) BindUavs(graphicsUavs_, uavStart, numUavs, uavs, initialCounts, true, call);
}

ContextImpl::OutputMergerSlots ContextImpl::SlotsAfter(UINT numRtvs, RenderTargetView* const* rtvs,
                                                      DepthStencilView* dsv, UINT uavStart, UINT numUavs,
                                                      UnorderedAccessView* const* uavs) const {
  const bool keepTargets = numRtvs == KEEP_RENDER_TARGETS_AND_DEPTH_STENCIL;
  const bool keepUavs = numUavs == KEEP_UNORDERED_ACCESS_VIEWS;
  OutputMergerSlots om;
  for (UINT i = 0; i < SIMULTANEOUS_RENDER_TARGET_COUNT; ++i) {
    if (keepTargets) {
      om.targets[i] = renderTargets_[i] ? renderTargets_[i]->resource() : nullptr;
      if (om.targets[i]) om.targetCount = i + 1;
    } else if (i < numRtvs && rtvs && rtvs[i]) {
      om.targets[i] = static_cast<RenderTargetViewImpl*>(rtvs[i])->resource();
    }
  }
  if (!keepTargets) om.targetCount = numRtvs;
  om.depth = keepTargets ? (depthStencil_ ? depthStencil_->resource() : nullptr)
                         : (dsv ? static_cast<DepthStencilViewImpl*>(dsv)->resource() : nullptr);
  for (UINT i = 0; i < PS_CS_UAV_REGISTER_COUNT; ++i) {
    if (keepUavs)
      om.uavs[i] = graphicsUavs_[i] ? graphicsUavs_[i]->resource() : nullptr;
    else if (i >= uavStart && i - uavStart < numUavs && uavs && uavs[i - uavStart])
      om.uavs[i] = static_cast<UnorderedAccessViewImpl*>(uavs[i - uavStart])->resource();
    if (om.uavs[i]) om.firstUav = std::min(om.firstUav, i);
  }
  // D3D11 checks the UAV range it is given, empty slots included.
  if (!keepUavs && numUavs > 0) om.firstUav = std::min(om.firstUav, uavStart);
  return om;
}

std::string ContextImpl::CheckOutputMergerBinding(UINT numRtvs, RenderTargetView* const* rtvs, DepthStencilView* dsv,
                                                  UINT uavStart, UINT numUavs,
                                                  UnorderedAccessView* const* uavs) const {
  if (numRtvs != KEEP_RENDER_TARGETS_AND_DEPTH_STENCIL && numRtvs > SIMULTANEOUS_RENDER_TARGET_COUNT)
    return "NumRTVs (" + std::to_string(numRtvs) + ") exceeds SIMULTANEOUS_RENDER_TARGET_COUNT (8)";
  if (numUavs != KEEP_UNORDERED_ACCESS_VIEWS && numUavs > 0 &&
      (uavStart >= PS_CS_UAV_REGISTER_COUNT || numUavs > PS_CS_UAV_REGISTER_COUNT - uavStart))
    return "UAVStartSlot (" + std::to_string(uavStart) + ") + NumUAVs (" + std::to_string(numUavs) +
           ") exceeds the 8 UAV slots of feature level 11_0";
  const OutputMergerSlots om = SlotsAfter(numRtvs, rtvs, dsv, uavStart, numUavs, uavs);
  if (om.firstUav < om.targetCount)
    return "UAVStartSlot (" + std::to_string(om.firstUav) + ") must be at least NumRTVs (" +
           std::to_string(om.targetCount) + "): render targets and UAVs share the output merger's 8 slots";
  for (UINT u = 0; u < PS_CS_UAV_REGISTER_COUNT; ++u) {
    if (!om.uavs[u]) continue;
    for (UINT t = 0; t < SIMULTANEOUS_RENDER_TARGET_COUNT; ++t)
      if (om.targets[t] == om.uavs[u])
        return "the resource of UAV slot " + std::to_string(u) + " is also render target " + std::to_string(t) +
               "; a resource cannot be a render target and an unordered access view at once";
    if (om.depth == om.uavs[u])
      return "the resource of UAV slot " + std::to_string(u) +
             " is also the depth-stencil view's; a resource cannot be written through both at once";
  }
  return "";
}

void ContextImpl::OMGetRenderTargetsAndUnorderedAccessViews(UINT NumRTVs, RenderTargetView** ppRenderTargetViews,
                                                            DepthStencilView** ppDepthStencilView, UINT UAVStartSlot,
                                                            UINT NumUAVs, UnorderedAccessView** ppUnorderedAccessViews) {
  auto get = [](auto* object) {
    if (object) object->AddRef();
    return object;
  };
  for (UINT i = 0; ppRenderTargetViews && i < NumRTVs; ++i)
    ppRenderTargetViews[i] = i < renderTargets_.size() ? get(renderTargets_[i].Get()) : nullptr;
  if (ppDepthStencilView) *ppDepthStencilView = get(depthStencil_.Get());
  for (UINT i = 0; ppUnorderedAccessViews && i < NumUAVs; ++i)
    ppUnorderedAccessViews[i] = UAVStartSlot + i < graphicsUavs_.size() ? get(graphicsUavs_[UAVStartSlot + i].Get())
                                                                        : nullptr;
}

void ContextImpl::BindRenderTargets(const char* call, UINT count, RenderTargetView* const* views,
                                    DepthStencilView* depthView) {
  for (UINT i = 0; i < SIMULTANEOUS_RENDER_TARGET_COUNT; ++i) {
    auto* view = i < count && views ? static_cast<RenderTargetViewImpl*>(views[i]) : nullptr;
    if (view) UnbindFromReads(view->resource(), call);
    renderTargets_[i] = view;
  }
  auto* depth = static_cast<DepthStencilViewImpl*>(depthView);
  if (depth) UnbindFromReads(depth->resource(), call, WrittenAspects(*depth));
  depthStencil_ = depth;
  SetTargetsKey();
  renderTargetsChanged_ = true;
}

void ContextImpl::SetTargetsKey() {
  GraphicsPipelineKey& key = pipelineKey_;
  key.samples = 1;
  for (uint32_t i = 0; i < renderTargets_.size(); ++i) {
    key.colorFormats[i] = renderTargets_[i] ? renderTargets_[i]->format() : DXGI_FORMAT_UNKNOWN;
    if (renderTargets_[i]) key.samples = static_cast<uint16_t>(renderTargets_[i]->texture().shape().samples);
  }
  key.depthFormat = depthStencil_ ? depthStencil_->texture().vkFormat() : VK_FORMAT_UNDEFINED;
  key.dsvFlags = depthStencil_ ? static_cast<uint16_t>(depthStencil_->desc().Flags) : 0;
  if (depthStencil_) key.samples = static_cast<uint16_t>(depthStencil_->texture().shape().samples);
  PipelineStateChanged();
}

void ContextImpl::OMSetBlendState(BlendState* pBlendState, const FLOAT BlendFactor[4], UINT SampleMask) {
  auto* state = static_cast<BlendStateImpl*>(pBlendState);
  if (state != blendState_.Get() || SampleMask != sampleMask_) {
    blendState_ = state;
    sampleMask_ = SampleMask;
    pipelineKey_.blend = state ? state->contentId() : 0;
    pipelineKey_.sampleMask = SampleMask;
    PipelineStateChanged();
  }
  // D3D11: a NULL factor means (1,1,1,1).
  if (BlendFactor)
    std::copy(BlendFactor, BlendFactor + 4, blendFactor_.begin());
  else
    blendFactor_ = {1, 1, 1, 1};
  dynamicDirty_.blendConstants = true;
}

void ContextImpl::OMSetDepthStencilState(DepthStencilState* pDepthStencilState, UINT StencilRef) {
  auto* state = static_cast<DepthStencilStateImpl*>(pDepthStencilState);
  if (state != depthStencilState_.Get()) {
    depthStencilState_ = state;
    pipelineKey_.depthStencil = state ? state->contentId() : 0;
    PipelineStateChanged();
  }
  stencilRef_ = StencilRef;
  dynamicDirty_.stencilRef = true;
}

VkImageAspectFlags WrittenAspects(const DepthStencilViewImpl& view) {
  VkImageAspectFlags aspects = view.texture().aspects();
  if (view.desc().Flags & DSV_READ_ONLY_DEPTH) aspects &= ~VkImageAspectFlags(VK_IMAGE_ASPECT_DEPTH_BIT);
  if (view.desc().Flags & DSV_READ_ONLY_STENCIL) aspects &= ~VkImageAspectFlags(VK_IMAGE_ASPECT_STENCIL_BIT);
  return aspects;
}

bool ContextImpl::IsBoundForWriting(Resource* resource, VkImageAspectFlags aspects) const {
  if (!resource) return false;
  for (const auto& view : renderTargets_)
    if (view && view->resource() == resource) return true;
  if (depthStencil_ && depthStencil_->resource() == resource && (WrittenAspects(*depthStencil_) & aspects))
    return true;
  return IsBoundForStreamOutOrUav(resource);
}

bool ContextImpl::IsBoundForWriting(const BufferImpl* buffer) const {
  return buffer && IsBoundForStreamOutOrUav(buffer);
}

bool ContextImpl::IsBoundForStreamOutOrUav(const Resource* resource) const {
  for (const auto& target : streamOut_)
    if (target.buffer.Get() == resource) return true;
  return IsBoundAsUav(resource);
}

bool ContextImpl::IsBoundAsUav(const Resource* resource) const {
  for (const UavSlots* slots : {&computeUavs_, &graphicsUavs_})
    for (const auto& view : *slots)
      if (view && view->resource() == resource) return true;
  return false;
}

void ContextImpl::UnbindFromReads(Resource* resource, const char* call, VkImageAspectFlags aspects) {
  for (UavSlots* slots : {&computeUavs_, &graphicsUavs_})
    for (auto& view : *slots)
      if (view && view->resource() == resource) view.Reset();
  const std::string prefix = std::string(call) + ": the resource being bound for output is still bound on input; ";
  for (UINT slot = 0; slot < vertexBuffers_.size(); ++slot)
    if (vertexBuffers_[slot].buffer.Get() == resource) {
      vertexBuffers_[slot] = {};
      vertexBuffersDirty_ = true;
      ReportHazard(prefix + "forcing vertex buffer slot " + std::to_string(slot) + " to NULL");
    }
  if (indexBuffer_.buffer.Get() == resource) {
    indexBuffer_ = {};
    ReportHazard(prefix + "forcing the index buffer to NULL");
  }
  for (uint32_t stage = 0; stage < kShaderStageCount; ++stage) {
    // spirv::Stage lists the stages in ShaderStage's order.
    const std::string stageName = spirv::StageName(static_cast<spirv::Stage>(stage));
    auto& state = stages_[stage];
    for (UINT slot = 0; slot < state.constantBuffers.size(); ++slot)
      if (state.constantBuffers[slot].Get() == resource) {
        state.constantBuffers[slot].Reset();
        ReportHazard(prefix + "forcing " + stageName + " constant buffer slot " + std::to_string(slot) + " to NULL");
      }
    // A texture's shader-resource view reads one aspect; a read-only depth-stencil view writes neither.
    for (UINT slot = 0; slot < state.shaderResources.size(); ++slot) {
      const auto& view = state.shaderResources[slot];
      if (view && view->resource() == resource && (view->buffer() || (view->range().aspectMask & aspects))) {
        state.shaderResources[slot].Reset();
        ReportHazard(prefix + "forcing " + stageName + " shader resource slot " + std::to_string(slot) + " to NULL");
      }
    }
  }
  descriptorsDirty_ = true;
}

void ContextImpl::ClearState() {
  inputLayout_.Reset();
  pipelineKey_ = DefaultPipelineKey();
  PipelineStateChanged();
  vertexBuffers_ = {};
  indexBuffer_ = {};
  topology_ = PRIMITIVE_TOPOLOGY_UNDEFINED;
  stages_ = {};
  computeUavs_ = {};
  graphicsUavs_ = {};
  streamOut_ = {};
  rasterizer_.Reset();
  viewports_.clear();
  scissors_.clear();
  renderTargets_ = {};
  depthStencil_.Reset();
  blendState_.Reset();
  blendFactor_ = {1, 1, 1, 1};
  sampleMask_ = DEFAULT_SAMPLE_MASK;
  depthStencilState_.Reset();
  stencilRef_ = 0;
  predicate_.Reset();
  predicateValue_ = FALSE;
  predicationSkips_ = false;
  renderTargetsChanged_ = descriptorsDirty_ = vertexBuffersDirty_ = true;
  dynamicDirty_.All();
}

void ContextImpl::ReportHazard(const std::string& text) {
  device_->gpu().Report(MESSAGE_CATEGORY_STATE_SETTING, MESSAGE_SEVERITY_WARNING, text);
}

void ContextImpl::ReportDrawError(const std::string& text) {
  device_->gpu().Report(MESSAGE_CATEGORY_EXECUTION, MESSAGE_SEVERITY_ERROR, text);
}

}  // namespace rhi::vk
