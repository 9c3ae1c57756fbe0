// The immediate context: D3D11 binding state, recorded into Vulkan commands.
//
// Binding calls only store state and mark it dirty. A draw turns the state into
// a pipeline (looked up in the cache), barriers for every resource it touches,
// a dynamic-rendering instance (begun lazily, ended only when something needs
// it ended), push descriptors and the draw itself.
#pragma once

#include <array>
#include <tuple>
#include <vector>

#include "device.h"
#include "pipelines.h"
#include "resource_tracking.h"
#include "rhi/shader_bindings.h"

namespace rhi::vk {

class BufferImpl;
class TextureStorage;
template <class Interface, class Desc>
class ViewImpl;
using ShaderResourceViewImpl = ViewImpl<ShaderResourceView, SHADER_RESOURCE_VIEW_DESC>;
using RenderTargetViewImpl = ViewImpl<RenderTargetView, RENDER_TARGET_VIEW_DESC>;
using DepthStencilViewImpl = ViewImpl<DepthStencilView, DEPTH_STENCIL_VIEW_DESC>;
class UnorderedAccessViewImpl;
template <class Interface, class Desc>
class StateObject;
using BlendStateImpl = StateObject<BlendState, BLEND_DESC>;
using DepthStencilStateImpl = StateObject<DepthStencilState, DEPTH_STENCIL_DESC>;
using RasterizerStateImpl = StateObject<RasterizerState, RASTERIZER_DESC>;
class SamplerStateImpl;
class InputLayoutImpl;
class ShaderCode;
class QueryImpl;
class QueryTracker;

// The aspects of its texture that draws may write through `view`: a
// DSV_READ_ONLY_DEPTH / _STENCIL view writes none of that aspect.
VkImageAspectFlags WrittenAspects(const DepthStencilViewImpl& view);

class ContextImpl final : public DeviceContext {
 public:
  explicit ContextImpl(DeviceImpl* device);
  ~ContextImpl() override;

  // The immediate context lives and dies with its device.
  UINT AddRef() override { return device_->AddRef(); }
  UINT Release() override { return device_->Release(); }
  void GetDevice(Device** ppDevice) override {
    device_->AddRef();
    *ppDevice = device_;
  }

  void IASetInputLayout(InputLayout* pInputLayout) override;
  void IASetVertexBuffers(UINT StartSlot, UINT NumBuffers, Buffer* const* ppVertexBuffers, const UINT* pStrides,
                          const UINT* pOffsets) override;
  void IASetIndexBuffer(Buffer* pIndexBuffer, DXGI_FORMAT Format, UINT Offset) override;
  void IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY Topology) override;
  // The getters (context_getters.cpp).
  void IAGetInputLayout(InputLayout** ppInputLayout) override;
  void IAGetVertexBuffers(UINT StartSlot, UINT NumBuffers, Buffer** ppVertexBuffers, UINT* pStrides,
                          UINT* pOffsets) override;
  void IAGetIndexBuffer(Buffer** pIndexBuffer, DXGI_FORMAT* Format, UINT* Offset) override;
  void IAGetPrimitiveTopology(PRIMITIVE_TOPOLOGY* pTopology) override;
  void VSGetShader(VertexShader** ppShader, ClassInstance** ppClassInstances, UINT* pNumClassInstances) override;
  void HSGetShader(HullShader** ppShader, ClassInstance** ppClassInstances, UINT* pNumClassInstances) override;
  void DSGetShader(DomainShader** ppShader, ClassInstance** ppClassInstances, UINT* pNumClassInstances) override;
  void GSGetShader(GeometryShader** ppShader, ClassInstance** ppClassInstances, UINT* pNumClassInstances) override;
  void PSGetShader(PixelShader** ppShader, ClassInstance** ppClassInstances, UINT* pNumClassInstances) override;
  void CSGetShader(ComputeShader** ppShader, ClassInstance** ppClassInstances, UINT* pNumClassInstances) override;
  void CSGetUnorderedAccessViews(UINT StartSlot, UINT NumUAVs, UnorderedAccessView** ppUnorderedAccessViews) override;
  void RSGetState(RasterizerState** ppRasterizerState) override;
  void RSGetViewports(UINT* pNumViewports, VIEWPORT* pViewports) override;
  void RSGetScissorRects(UINT* pNumRects, RECT* pRects) override;
  void OMGetRenderTargets(UINT NumViews, RenderTargetView** ppRenderTargetViews,
                          DepthStencilView** ppDepthStencilView) override;
  void OMGetBlendState(BlendState** ppBlendState, FLOAT BlendFactor[4], UINT* pSampleMask) override;
  void OMGetDepthStencilState(DepthStencilState** ppDepthStencilState, UINT* pStencilRef) override;

  void VSSetShader(VertexShader* pShader, ClassInstance* const*, UINT) override;
  void HSSetShader(HullShader* pShader, ClassInstance* const*, UINT) override;
  void DSSetShader(DomainShader* pShader, ClassInstance* const*, UINT) override;
  void GSSetShader(GeometryShader* pShader, ClassInstance* const*, UINT) override;
  void PSSetShader(PixelShader* pShader, ClassInstance* const*, UINT) override;
  void CSSetShader(ComputeShader* pShader, ClassInstance* const*, UINT) override;

#define RHI_STAGE_BINDINGS(Prefix, Stage)                                                                 \
  void Prefix##SetConstantBuffers(UINT StartSlot, UINT NumBuffers, Buffer* const* ppBuffers) override {   \
    SetConstantBuffers(ShaderStage::Stage, StartSlot, NumBuffers, ppBuffers);                            \
  }                                                                                                       \
  void Prefix##SetShaderResources(UINT StartSlot, UINT NumViews, ShaderResourceView* const* ppViews) override { \
    SetShaderResources(ShaderStage::Stage, StartSlot, NumViews, ppViews);                                \
  }                                                                                                       \
  void Prefix##SetSamplers(UINT StartSlot, UINT NumSamplers, SamplerState* const* ppSamplers) override {  \
    SetSamplers(ShaderStage::Stage, StartSlot, NumSamplers, ppSamplers);                                 \
  }                                                                                                       \
  void Prefix##GetConstantBuffers(UINT StartSlot, UINT NumBuffers, Buffer** ppBuffers) override {         \
    GetConstantBuffers(ShaderStage::Stage, StartSlot, NumBuffers, ppBuffers);                            \
  }                                                                                                       \
  void Prefix##GetShaderResources(UINT StartSlot, UINT NumViews, ShaderResourceView** ppViews) override { \
    GetShaderResources(ShaderStage::Stage, StartSlot, NumViews, ppViews);                                \
  }                                                                                                       \
  void Prefix##GetSamplers(UINT StartSlot, UINT NumSamplers, SamplerState** ppSamplers) override {        \
    GetSamplers(ShaderStage::Stage, StartSlot, NumSamplers, ppSamplers);                                 \
  }
  RHI_STAGE_BINDINGS(VS, Vertex)
  RHI_STAGE_BINDINGS(HS, Hull)
  RHI_STAGE_BINDINGS(DS, Domain)
  RHI_STAGE_BINDINGS(GS, Geometry)
  RHI_STAGE_BINDINGS(PS, Pixel)
  RHI_STAGE_BINDINGS(CS, Compute)
#undef RHI_STAGE_BINDINGS
  void CSSetUnorderedAccessViews(UINT StartSlot, UINT NumUAVs, UnorderedAccessView* const* ppUAVs,
                                 const UINT* pUAVInitialCounts) override;

  void SOSetTargets(UINT NumBuffers, Buffer* const* ppSOTargets, const UINT* pOffsets) override;
  void SOGetTargets(UINT NumBuffers, Buffer** ppSOTargets) override;

  void RSSetState(RasterizerState* pRasterizerState) override;
  void RSSetViewports(UINT NumViewports, const VIEWPORT* pViewports) override;
  void RSSetScissorRects(UINT NumRects, const RECT* pRects) override;

  void OMSetRenderTargets(UINT NumViews, RenderTargetView* const* ppRenderTargetViews,
                          DepthStencilView* pDepthStencilView) override;
  void OMSetRenderTargetsAndUnorderedAccessViews(UINT NumRTVs, RenderTargetView* const* ppRenderTargetViews,
                                                 DepthStencilView* pDepthStencilView, UINT UAVStartSlot, UINT NumUAVs,
                                                 UnorderedAccessView* const* ppUnorderedAccessViews,
                                                 const UINT* pUAVInitialCounts) override;
  void OMGetRenderTargetsAndUnorderedAccessViews(UINT NumRTVs, RenderTargetView** ppRenderTargetViews,
                                                 DepthStencilView** ppDepthStencilView, UINT UAVStartSlot,
                                                 UINT NumUAVs, UnorderedAccessView** ppUnorderedAccessViews) override;
  void OMSetBlendState(BlendState* pBlendState, const FLOAT BlendFactor[4], UINT SampleMask) override;
  void OMSetDepthStencilState(DepthStencilState* pDepthStencilState, UINT StencilRef) override;

  void Draw(UINT VertexCount, UINT StartVertexLocation) override;
  void DrawIndexed(UINT IndexCount, UINT StartIndexLocation, INT BaseVertexLocation) override;
  void DrawInstanced(UINT VertexCountPerInstance, UINT InstanceCount, UINT StartVertexLocation,
                     UINT StartInstanceLocation) override;
  void DrawIndexedInstanced(UINT IndexCountPerInstance, UINT InstanceCount, UINT StartIndexLocation,
                            INT BaseVertexLocation, UINT StartInstanceLocation) override;
  void DrawInstancedIndirect(Buffer* pBufferForArgs, UINT AlignedByteOffsetForArgs) override;
  void DrawIndexedInstancedIndirect(Buffer* pBufferForArgs, UINT AlignedByteOffsetForArgs) override;
  void DrawAuto() override;
  void Dispatch(UINT ThreadGroupCountX, UINT ThreadGroupCountY, UINT ThreadGroupCountZ) override;
  void DispatchIndirect(Buffer* pBufferForArgs, UINT AlignedByteOffsetForArgs) override;

  void ClearRenderTargetView(RenderTargetView* pRenderTargetView, const FLOAT ColorRGBA[4]) override;
  void ClearDepthStencilView(DepthStencilView* pDepthStencilView, UINT ClearFlags, FLOAT Depth,
                             UINT8 Stencil) override;
  void ClearUnorderedAccessViewUint(UnorderedAccessView* pUnorderedAccessView, const UINT Values[4]) override;
  void ClearUnorderedAccessViewFloat(UnorderedAccessView* pUnorderedAccessView, const FLOAT Values[4]) override;

  HRESULT Map(Resource* pResource, UINT Subresource, MAP MapType, UINT MapFlags,
              MAPPED_SUBRESOURCE* pMappedResource) override;
  void Unmap(Resource* pResource, UINT Subresource) override;
  void UpdateSubresource(Resource* pDstResource, UINT DstSubresource, const BOX* pDstBox, const void* pSrcData,
                         UINT SrcRowPitch, UINT SrcDepthPitch) override;
  void CopyResource(Resource* pDstResource, Resource* pSrcResource) override;
  void CopySubresourceRegion(Resource* pDstResource, UINT DstSubresource, UINT DstX, UINT DstY, UINT DstZ,
                             Resource* pSrcResource, UINT SrcSubresource, const BOX* pSrcBox) override;
  void ResolveSubresource(Resource* pDstResource, UINT DstSubresource, Resource* pSrcResource,
                          UINT SrcSubresource, DXGI_FORMAT Format) override;
  void CopyStructureCount(Buffer* pDstBuffer, UINT DstAlignedByteOffset, UnorderedAccessView* pSrcView) override;
  void GenerateMips(ShaderResourceView* pShaderResourceView) override;  // texture_misc.cpp
  void SetResourceMinLOD(Resource* pResource, FLOAT MinLOD) override;   // texture_misc.cpp
  FLOAT GetResourceMinLOD(Resource* pResource) override;                // texture_misc.cpp

  void Begin(Asynchronous* pAsync) override;
  void End(Asynchronous* pAsync) override;
  HRESULT GetData(Asynchronous* pAsync, void* pData, UINT DataSize, UINT GetDataFlags) override;
  // predication.cpp
  void SetPredication(Predicate* pPredicate, BOOL PredicateValue) override;
  void GetPredication(Predicate** ppPredicate, BOOL* pPredicateValue) override;

  void ClearState() override;
  void Flush() override;
  DEVICE_CONTEXT_TYPE GetType() override { return DEVICE_CONTEXT_IMMEDIATE; }
  UINT GetContextFlags() override { return 0; }
  // deferred_context.cpp
  void ExecuteCommandList(CommandList* pCommandList, BOOL RestoreContextState) override;
  HRESULT FinishCommandList(BOOL RestoreDeferredContextState, CommandList** ppCommandList) override;
  // Debug-utils labels (context_annotations.cpp).
  void BeginEvent(const char* name) override;
  void EndEvent() override;
  void SetMarker(const char* name) override;
  // A query destroyed while active leaves the active sets.
  void ForgetQuery(QueryImpl& query);

  // Device-side uploads (initial data) go through the context's command stream.
  void UploadBuffer(BufferImpl& buffer, VkDeviceSize offset, const void* data, VkDeviceSize size);
  void UploadTexture(TextureStorage& texture, UINT subresource, const BOX* box, const void* data, UINT rowPitch,
                     UINT depthPitch);
  void InitializeImageLayout(TextureStorage& texture);

  // Records `use` of `resource`, adding the barrier it needs to the pending batch.
  // `attachmentInstance`: the rendering instance an attachment write happens in.
  void Use(TrackedResource& resource, const Access& use, uint64_t attachmentInstance = 0) {
    resource.Use(use, attachmentInstance, &pendingBarrier_);
    resource.lastUseSerial = device_->gpu().RecordingSerial();
  }
  // Emits the pending barrier batch; ends rendering first when there is one.
  void FlushBarriers() {
    if (pendingBarrier_.srcStageMask != 0 || pendingBarrier_.dstStageMask != 0) EmitBarriers();
  }
  // Ends the current rendering instance, if any (transfers and barriers need that).
  void EndRendering();
  VkCommandBuffer Commands() { return device_->gpu().Commands(); }

 private:
  struct VertexBufferBinding {
    Bound<BufferImpl> buffer;
    UINT stride = 0;
    UINT offset = 0;
  };
  struct IndexBufferBinding {
    Bound<BufferImpl> buffer;
    DXGI_FORMAT format = DXGI_FORMAT_UNKNOWN;
    UINT offset = 0;
  };
  struct StageState {
    const ShaderCode* shader = nullptr;  // owned by the shader object
    Bound<Bindable> shaderObject;        // keeps the D3D object (and its code) alive while bound
    std::array<Bound<BufferImpl>, COMMONSHADER_CONSTANT_BUFFER_API_SLOT_COUNT> constantBuffers;
    std::array<Bound<ShaderResourceViewImpl>, COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT> shaderResources;
    std::array<Bound<SamplerStateImpl>, COMMONSHADER_SAMPLER_SLOT_COUNT> samplers;
  };
  struct StreamOutTarget {
    Bound<BufferImpl> buffer;
    UINT offset = 0;  // UINT(-1): append where the last stream-out stopped
    bool offsetPending = false;  // the next stream-out starts at `offset`, not at the counter
  };

  void SetShader(ShaderStage stage, Bindable* object, const ShaderCode* code);
  void SetConstantBuffers(ShaderStage stage, UINT start, UINT count, Buffer* const* buffers);
  void SetShaderResources(ShaderStage stage, UINT start, UINT count, ShaderResourceView* const* views);
  void SetSamplers(ShaderStage stage, UINT start, UINT count, SamplerState* const* samplers);
  void GetConstantBuffers(ShaderStage stage, UINT start, UINT count, Buffer** buffers);
  void GetShaderResources(ShaderStage stage, UINT start, UINT count, ShaderResourceView** views);
  void GetSamplers(ShaderStage stage, UINT start, UINT count, SamplerState** samplers);
  void EmitBarriers();
  // ResolveSubresource as `format` where an image stores another member of its
  // typeless family: a rendering instance with a resolve attachment.
  void ResolveThroughRendering(TextureStorage& dst, UINT dstSub, TextureStorage& src, UINT srcSub, VkFormat format);
  using UavSlots = std::array<Bound<UnorderedAccessViewImpl>, PS_CS_UAV_REGISTER_COUNT>;
  // D3D11's hazard rule: a resource bound for writing leaves every read binding
  // and every UAV slot (of either pipeline), with a warning for each read binding
  // it empties (DEVICE_*_HAZARD), naming `call`. `aspects`: those the output
  // writes; shader-resource views of other aspects stay bound.
  void UnbindFromReads(Resource* resource, const char* call, VkImageAspectFlags aspects = ~VkImageAspectFlags{0});
  void ReportHazard(const std::string& text);
  // Compute UAVs for the compute stage, output-merger UAVs for the graphics stages.
  const UavSlots& UavsOf(ShaderStage stage) const {
    return stage == ShaderStage::Compute ? computeUavs_ : graphicsUavs_;
  }
  // Binds `count` views from `start`; the other slots are emptied when `unbindOthers`
  // (the output merger's rule), else kept (CSSetUnorderedAccessViews).
  void BindUavs(UavSlots& slots, UINT start, UINT count, UnorderedAccessView* const* views,
                const UINT* initialCounts, bool unbindOthers, const char* call);
  // Sets a view's hidden counter on the GPU (pUAVInitialCounts); UINT(-1) keeps it.
  void SetUavCounter(UnorderedAccessViewImpl& view, UINT count);
  // OMSetRenderTargets and OMSetRenderTargetsAndUnorderedAccessViews; `call` names the one used.
  void SetOutputMerger(const char* call, UINT numRtvs, RenderTargetView* const* rtvs, DepthStencilView* dsv,
                       UINT uavStart, UINT numUavs, UnorderedAccessView* const* uavs, const UINT* initialCounts);
  void BindRenderTargets(const char* call, UINT count, RenderTargetView* const* views, DepthStencilView* depth);
  // The resources in the output merger's slots after such a call: the new
  // views, or the bound ones where NumRTVs / NumUAVs are KEEP_*.
  struct OutputMergerSlots {
    std::array<Resource*, SIMULTANEOUS_RENDER_TARGET_COUNT> targets{};
    UINT targetCount = 0;  // NumRTVs, or the bound count: the first slot a UAV may take
    Resource* depth = nullptr;
    std::array<Resource*, PS_CS_UAV_REGISTER_COUNT> uavs{};
    UINT firstUav = PS_CS_UAV_REGISTER_COUNT;  // the lowest UAV slot the call binds or keeps
  };
  OutputMergerSlots SlotsAfter(UINT numRtvs, RenderTargetView* const* rtvs, DepthStencilView* dsv, UINT uavStart,
                               UINT numUavs, UnorderedAccessView* const* uavs) const;
  // Why OMSetRenderTargetsAndUnorderedAccessViews must ignore these arguments, or "".
  std::string CheckOutputMergerBinding(UINT numRtvs, RenderTargetView* const* rtvs, DepthStencilView* dsv,
                                       UINT uavStart, UINT numUavs, UnorderedAccessView* const* uavs) const;
  bool IsBoundForWriting(Resource* resource, VkImageAspectFlags aspects = ~VkImageAspectFlags{0}) const;
  // Render targets and depth-stencil views are texture-only: a buffer is written
  // only through stream output and UAVs (the IA setters' check, on every draw).
  bool IsBoundForWriting(const BufferImpl* buffer) const;
  bool IsBoundForStreamOutOrUav(const Resource* resource) const;
  bool IsBoundAsUav(const Resource* resource) const;

  // Draw path (context_draw.cpp).
  // `indirect`: the buffer a draw reads its arguments from, and how.
  const GraphicsPipeline* PrepareDraw(const char* call, TrackedResource* indirect = nullptr,
                                      const Access& indirectUse = uses::kIndirectArgs);
  void TrackDrawResources(const char* call, const GraphicsPipeline& pipeline, TrackedResource* indirect,
                          const Access& indirectUse);
  // A shader's use of UAV register `reg` (or of its hidden counter): a read and
  // a write. `call` reports a counter used through a view that has none.
  void UseUav(const char* call, const RegisterSlot& reg, VkPipelineStageFlags2 stages);
  // Finds the pipeline of pipelineKey_, or builds it from the bound state.
  const GraphicsPipeline* LookUpPipeline(const char* call);
  // The key's render-target formats and sample count, from the bound views.
  void SetTargetsKey();
  // A key setter changed the key: the current pipeline must be looked up again.
  void PipelineStateChanged() { currentPipeline_ = nullptr; }
  void BeginRendering();
  void BindGraphicsState(const GraphicsPipeline& pipeline);
  void SetViewportsAndScissors();
  void BindVertexAndIndexBuffers(const GraphicsPipeline& pipeline);
  void PushDescriptors(VkPipelineBindPoint bindPoint, const PipelineLayout& layout);
  void WriteViewDescriptor(size_t i, const RegisterSlot& reg, const StageState& stage);
  const ComputePipeline* PrepareDispatch(const char* call);
  void BindCompute(const ComputePipeline& pipeline);
  VkSampler defaultSampler();
  void ReportDrawError(const std::string& text);
  // Stream output (context_stream_out.cpp).
  void PrepareStreamOutTargets();
  void BeginStreamOut(const GraphicsPipeline& pipeline);
  void EndStreamOut(const GraphicsPipeline& pipeline);
  void WriteDrawAutoArgs(BufferImpl& buffer, UINT stride, UINT vertexBufferOffset);

  DeviceImpl* device_;

  Bound<InputLayoutImpl> inputLayout_;
  std::array<VertexBufferBinding, IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT> vertexBuffers_;
  IndexBufferBinding indexBuffer_;
  PRIMITIVE_TOPOLOGY topology_ = PRIMITIVE_TOPOLOGY_UNDEFINED;
  std::array<StageState, kShaderStageCount> stages_;
  UavSlots computeUavs_;
  UavSlots graphicsUavs_;  // OMSetRenderTargetsAndUnorderedAccessViews
  std::array<StreamOutTarget, SO_BUFFER_SLOT_COUNT> streamOut_;
  Bound<RasterizerStateImpl> rasterizer_;
  std::vector<VIEWPORT> viewports_;
  std::vector<RECT> scissors_;
  std::array<Bound<RenderTargetViewImpl>, SIMULTANEOUS_RENDER_TARGET_COUNT> renderTargets_;
  Bound<DepthStencilViewImpl> depthStencil_;
  Bound<BlendStateImpl> blendState_;
  std::array<FLOAT, 4> blendFactor_{1, 1, 1, 1};
  UINT sampleMask_ = DEFAULT_SAMPLE_MASK;
  Bound<DepthStencilStateImpl> depthStencilState_;
  UINT stencilRef_ = 0;

  // Recording state.
  VkMemoryBarrier2 pendingBarrier_{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  bool rendering_ = false;
  uint64_t renderingInstance_ = 0;
  VkExtent2D renderArea_{1, 1};
  VkSampler defaultSampler_ = VK_NULL_HANDLE;
  std::tuple<std::vector<VkWriteDescriptorSet>, std::vector<VkDescriptorBufferInfo>,
             std::vector<VkDescriptorImageInfo>, std::vector<VkBufferView>>
      descriptorScratch_;
  bool renderTargetsChanged_ = true;
  const GraphicsPipeline* boundPipeline_ = nullptr;
  // The pipeline key of the bound state, kept up to date by the setters that
  // enter it (shaders, layout, states, targets, sample mask, topology), so a
  // draw does not rebuild it.
  GraphicsPipelineKey pipelineKey_ = DefaultPipelineKey();
  // The pipeline of pipelineKey_; looked up again only after the key changed.
  const GraphicsPipeline* currentPipeline_ = nullptr;
  // Vulkan dynamic state that must be recorded again. It survives pipeline
  // binds (every pipeline declares it dynamic), except viewport and scissor,
  // which pipelines that rasterize nothing lack.
  struct DynamicStateDirty {
    bool viewport = true, topology = true, stencilRef = true, blendConstants = true;
    void All() { viewport = topology = stencilRef = blendConstants = true; }
  } dynamicDirty_;
  bool descriptorsDirty_ = true;
  bool vertexBuffersDirty_ = true;
  std::unique_ptr<QueryTracker> queries_;
  // SetPredication: the predicate, its value, and whether its result equals
  // the value, so that predicated calls are skipped.
  Bound<QueryImpl> predicate_;
  BOOL predicateValue_ = FALSE;
  bool predicationSkips_ = false;
};

}  // namespace rhi::vk
