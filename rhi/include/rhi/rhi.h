// The Direct3D 11-shaped rendering API.
//
// Interfaces mirror ID3D11Device / ID3D11DeviceContext: the same methods, the
// same parameter order, the same HRESULTs, the same binding rules. Porting D3D11
// code means dropping the `ID3D11` / `D3D11_` prefixes. Differences, all forced
// by the platform:
//  - shader "bytecode" is SPIR-V (compile HLSL with effects/hlsl);
//  - there is no DXGI: CreateDevice picks a Vulkan device (lavapipe by default),
//    and windows go through rhi/swap_chain.h;
//  - the D3D11 debug layer's messages arrive through DEVICE_OPTIONS::OnMessage,
//    together with the Vulkan validation layer's;
//  - device children do not keep the device alive (the context's bindings
//    would otherwise form reference cycles): release them before the device.
// The Vulkan implementation lives in rhi/src and never leaks through here.
#pragma once

#include <atomic>
#include <functional>
#include <utility>

#include "rhi/d3d11_types.h"

namespace rhi {

// ---------------------------------------------------------------------------
// Reference counting (IUnknown without QueryInterface)

class Unknown {
 public:
  virtual UINT AddRef() { return ++refCount_; }
  virtual UINT Release() {
    UINT left = --refCount_;
    if (left == 0) delete this;
    return left;
  }

 protected:
  Unknown() = default;
  virtual ~Unknown() = default;
  Unknown(const Unknown&) = delete;
  Unknown& operator=(const Unknown&) = delete;

 private:
  std::atomic<UINT> refCount_{1};
};

// Microsoft::WRL::ComPtr, reduced to what ports use.
template <class T>
class ComPtr {
 public:
  ComPtr() = default;
  ComPtr(std::nullptr_t) {}
  ComPtr(T* p) : ptr_(p) { if (ptr_) ptr_->AddRef(); }
  ComPtr(const ComPtr& o) : ComPtr(o.ptr_) {}
  ComPtr(ComPtr&& o) noexcept : ptr_(std::exchange(o.ptr_, nullptr)) {}
  ~ComPtr() { Reset(); }
  ComPtr& operator=(ComPtr o) noexcept { std::swap(ptr_, o.ptr_); return *this; }

  T* Get() const { return ptr_; }
  T* operator->() const { return ptr_; }
  T& operator*() const { return *ptr_; }
  explicit operator bool() const { return ptr_ != nullptr; }
  T** GetAddressOf() { return &ptr_; }
  T** ReleaseAndGetAddressOf() { Reset(); return &ptr_; }
  void Reset() { if (auto* p = std::exchange(ptr_, nullptr)) p->Release(); }
  void Attach(T* p) { Reset(); ptr_ = p; }
  T* Detach() { return std::exchange(ptr_, nullptr); }

 private:
  T* ptr_ = nullptr;
};

// ---------------------------------------------------------------------------
// Device children

class Device;

class DeviceChild : public Unknown {
 public:
  virtual void GetDevice(Device** ppDevice) = 0;
};

enum RESOURCE_DIMENSION : UINT {
  RESOURCE_DIMENSION_UNKNOWN = 0,
  RESOURCE_DIMENSION_BUFFER = 1,
  RESOURCE_DIMENSION_TEXTURE1D = 2,
  RESOURCE_DIMENSION_TEXTURE2D = 3,
  RESOURCE_DIMENSION_TEXTURE3D = 4,
};

class Resource : public DeviceChild {
 public:
  virtual void GetType(RESOURCE_DIMENSION* pResourceDimension) = 0;
};

class Buffer : public Resource {
 public:
  virtual void GetDesc(BUFFER_DESC* pDesc) = 0;
};

class Texture1D : public Resource {
 public:
  virtual void GetDesc(TEXTURE1D_DESC* pDesc) = 0;
};

class Texture2D : public Resource {
 public:
  virtual void GetDesc(TEXTURE2D_DESC* pDesc) = 0;
};

class Texture3D : public Resource {
 public:
  virtual void GetDesc(TEXTURE3D_DESC* pDesc) = 0;
};

class View : public DeviceChild {
 public:
  virtual void GetResource(Resource** ppResource) = 0;
};

class ShaderResourceView : public View {
 public:
  virtual void GetDesc(SHADER_RESOURCE_VIEW_DESC* pDesc) = 0;
};

class RenderTargetView : public View {
 public:
  virtual void GetDesc(RENDER_TARGET_VIEW_DESC* pDesc) = 0;
};

class DepthStencilView : public View {
 public:
  virtual void GetDesc(DEPTH_STENCIL_VIEW_DESC* pDesc) = 0;
};

class UnorderedAccessView : public View {
 public:
  virtual void GetDesc(UNORDERED_ACCESS_VIEW_DESC* pDesc) = 0;
};

class VertexShader : public DeviceChild {};
class HullShader : public DeviceChild {};
class DomainShader : public DeviceChild {};
class GeometryShader : public DeviceChild {};
class PixelShader : public DeviceChild {};
class ComputeShader : public DeviceChild {};
class InputLayout : public DeviceChild {};

// Dynamic shader linkage is not supported; the parameters exist so calls port
// unchanged and must be null.
class ClassLinkage;
class ClassInstance;

class BlendState : public DeviceChild {
 public:
  virtual void GetDesc(BLEND_DESC* pDesc) = 0;
};

class DepthStencilState : public DeviceChild {
 public:
  virtual void GetDesc(DEPTH_STENCIL_DESC* pDesc) = 0;
};

class RasterizerState : public DeviceChild {
 public:
  virtual void GetDesc(RASTERIZER_DESC* pDesc) = 0;
};

class SamplerState : public DeviceChild {
 public:
  virtual void GetDesc(SAMPLER_DESC* pDesc) = 0;
};

class Asynchronous : public DeviceChild {
 public:
  virtual UINT GetDataSize() = 0;
};

class Query : public Asynchronous {
 public:
  virtual void GetDesc(QUERY_DESC* pDesc) = 0;
};

// A query whose BOOL result can predicate rendering (SetPredication).
class Predicate : public Query {};

// No counter can be created (CheckCounterInfo reports none); the type exists for CreateCounter's signature.
class Counter : public Asynchronous {
 public:
  virtual void GetDesc(COUNTER_DESC* pDesc) = 0;
};

// Commands recorded by a deferred context (FinishCommandList), run by the
// immediate context's ExecuteCommandList as often as wanted.
class CommandList : public DeviceChild {
 public:
  virtual UINT GetContextFlags() = 0;
};

// ---------------------------------------------------------------------------
// The immediate context, and deferred contexts (CreateDeferredContext)

class DeviceContext : public DeviceChild {
 public:
  // Input assembler
  virtual void IASetInputLayout(InputLayout* pInputLayout) = 0;
  virtual void IASetVertexBuffers(UINT StartSlot, UINT NumBuffers, Buffer* const* ppVertexBuffers,
                                  const UINT* pStrides, const UINT* pOffsets) = 0;
  virtual void IASetIndexBuffer(Buffer* pIndexBuffer, DXGI_FORMAT Format, UINT Offset) = 0;
  virtual void IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY Topology) = 0;
  virtual void IAGetInputLayout(InputLayout** ppInputLayout) = 0;
  virtual void IAGetVertexBuffers(UINT StartSlot, UINT NumBuffers, Buffer** ppVertexBuffers, UINT* pStrides,
                                  UINT* pOffsets) = 0;
  virtual void IAGetIndexBuffer(Buffer** pIndexBuffer, DXGI_FORMAT* Format, UINT* Offset) = 0;
  virtual void IAGetPrimitiveTopology(PRIMITIVE_TOPOLOGY* pTopology) = 0;

  // Shader stages
  virtual void VSSetShader(VertexShader* pShader, ClassInstance* const* ppClassInstances, UINT NumClassInstances) = 0;
  virtual void HSSetShader(HullShader* pShader, ClassInstance* const* ppClassInstances, UINT NumClassInstances) = 0;
  virtual void DSSetShader(DomainShader* pShader, ClassInstance* const* ppClassInstances, UINT NumClassInstances) = 0;
  virtual void GSSetShader(GeometryShader* pShader, ClassInstance* const* ppClassInstances, UINT NumClassInstances) = 0;
  virtual void PSSetShader(PixelShader* pShader, ClassInstance* const* ppClassInstances, UINT NumClassInstances) = 0;
  virtual void CSSetShader(ComputeShader* pShader, ClassInstance* const* ppClassInstances, UINT NumClassInstances) = 0;
  // pNumClassInstances (if not null) is set to 0: there are no class instances.
  virtual void VSGetShader(VertexShader** ppShader, ClassInstance** ppClassInstances, UINT* pNumClassInstances) = 0;
  virtual void HSGetShader(HullShader** ppShader, ClassInstance** ppClassInstances, UINT* pNumClassInstances) = 0;
  virtual void DSGetShader(DomainShader** ppShader, ClassInstance** ppClassInstances, UINT* pNumClassInstances) = 0;
  virtual void GSGetShader(GeometryShader** ppShader, ClassInstance** ppClassInstances, UINT* pNumClassInstances) = 0;
  virtual void PSGetShader(PixelShader** ppShader, ClassInstance** ppClassInstances, UINT* pNumClassInstances) = 0;
  virtual void CSGetShader(ComputeShader** ppShader, ClassInstance** ppClassInstances, UINT* pNumClassInstances) = 0;

#define RHI_DECLARE_STAGE_BINDINGS(Prefix)                                                                 \
  virtual void Prefix##SetConstantBuffers(UINT StartSlot, UINT NumBuffers, Buffer* const* ppConstantBuffers) = 0; \
  virtual void Prefix##SetShaderResources(UINT StartSlot, UINT NumViews,                                  \
                                          ShaderResourceView* const* ppShaderResourceViews) = 0;          \
  virtual void Prefix##SetSamplers(UINT StartSlot, UINT NumSamplers, SamplerState* const* ppSamplers) = 0; \
  virtual void Prefix##GetConstantBuffers(UINT StartSlot, UINT NumBuffers, Buffer** ppConstantBuffers) = 0;      \
  virtual void Prefix##GetShaderResources(UINT StartSlot, UINT NumViews,                                  \
                                          ShaderResourceView** ppShaderResourceViews) = 0;                \
  virtual void Prefix##GetSamplers(UINT StartSlot, UINT NumSamplers, SamplerState** ppSamplers) = 0;
  // The getters return what the setters bound, each object with a reference the
  // caller releases (null for an empty slot), as D3D11's do.
  RHI_DECLARE_STAGE_BINDINGS(VS)
  RHI_DECLARE_STAGE_BINDINGS(HS)
  RHI_DECLARE_STAGE_BINDINGS(DS)
  RHI_DECLARE_STAGE_BINDINGS(GS)
  RHI_DECLARE_STAGE_BINDINGS(PS)
  RHI_DECLARE_STAGE_BINDINGS(CS)
#undef RHI_DECLARE_STAGE_BINDINGS
  virtual void CSSetUnorderedAccessViews(UINT StartSlot, UINT NumUAVs,
                                         UnorderedAccessView* const* ppUnorderedAccessViews,
                                         const UINT* pUAVInitialCounts) = 0;
  virtual void CSGetUnorderedAccessViews(UINT StartSlot, UINT NumUAVs, UnorderedAccessView** ppUnorderedAccessViews) = 0;

  // Stream output
  virtual void SOSetTargets(UINT NumBuffers, Buffer* const* ppSOTargets, const UINT* pOffsets) = 0;
  virtual void SOGetTargets(UINT NumBuffers, Buffer** ppSOTargets) = 0;

  // Rasterizer
  virtual void RSSetState(RasterizerState* pRasterizerState) = 0;
  virtual void RSSetViewports(UINT NumViewports, const VIEWPORT* pViewports) = 0;
  virtual void RSSetScissorRects(UINT NumRects, const RECT* pRects) = 0;
  virtual void RSGetState(RasterizerState** ppRasterizerState) = 0;
  // With pViewports null, *pNumViewports receives the bound count; else
  // *pNumViewports are written, zeros past the bound ones. RSGetScissorRects likewise.
  virtual void RSGetViewports(UINT* pNumViewports, VIEWPORT* pViewports) = 0;
  virtual void RSGetScissorRects(UINT* pNumRects, RECT* pRects) = 0;

  // Output merger
  virtual void OMSetRenderTargets(UINT NumViews, RenderTargetView* const* ppRenderTargetViews,
                                  DepthStencilView* pDepthStencilView) = 0;
  // Render targets and pixel-shader UAVs share the output merger's 8 slots: UAVStartSlot must not be
  // below the render-target count. NumRTVs = KEEP_RENDER_TARGETS_AND_DEPTH_STENCIL and NumUAVs =
  // KEEP_UNORDERED_ACCESS_VIEWS leave those bindings as they are; pUAVInitialCounts sets the hidden
  // counters of append/counter UAVs (UINT(-1): keep the current count).
  virtual void OMSetRenderTargetsAndUnorderedAccessViews(UINT NumRTVs, RenderTargetView* const* ppRenderTargetViews,
                                                         DepthStencilView* pDepthStencilView, UINT UAVStartSlot,
                                                         UINT NumUAVs,
                                                         UnorderedAccessView* const* ppUnorderedAccessViews,
                                                         const UINT* pUAVInitialCounts) = 0;
  // Each returned view carries a reference; null pointers skip that part.
  virtual void OMGetRenderTargetsAndUnorderedAccessViews(UINT NumRTVs, RenderTargetView** ppRenderTargetViews,
                                                         DepthStencilView** ppDepthStencilView, UINT UAVStartSlot,
                                                         UINT NumUAVs,
                                                         UnorderedAccessView** ppUnorderedAccessViews) = 0;
  virtual void OMSetBlendState(BlendState* pBlendState, const FLOAT BlendFactor[4], UINT SampleMask) = 0;
  virtual void OMSetDepthStencilState(DepthStencilState* pDepthStencilState, UINT StencilRef) = 0;
  virtual void OMGetRenderTargets(UINT NumViews, RenderTargetView** ppRenderTargetViews,
                                  DepthStencilView** ppDepthStencilView) = 0;
  virtual void OMGetBlendState(BlendState** ppBlendState, FLOAT BlendFactor[4], UINT* pSampleMask) = 0;
  virtual void OMGetDepthStencilState(DepthStencilState** ppDepthStencilState, UINT* pStencilRef) = 0;

  // Draws and dispatches
  virtual void Draw(UINT VertexCount, UINT StartVertexLocation) = 0;
  virtual void DrawIndexed(UINT IndexCount, UINT StartIndexLocation, INT BaseVertexLocation) = 0;
  virtual void DrawInstanced(UINT VertexCountPerInstance, UINT InstanceCount, UINT StartVertexLocation,
                             UINT StartInstanceLocation) = 0;
  virtual void DrawIndexedInstanced(UINT IndexCountPerInstance, UINT InstanceCount, UINT StartIndexLocation,
                                    INT BaseVertexLocation, UINT StartInstanceLocation) = 0;
  virtual void DrawInstancedIndirect(Buffer* pBufferForArgs, UINT AlignedByteOffsetForArgs) = 0;
  virtual void DrawIndexedInstancedIndirect(Buffer* pBufferForArgs, UINT AlignedByteOffsetForArgs) = 0;
  virtual void DrawAuto() = 0;
  virtual void Dispatch(UINT ThreadGroupCountX, UINT ThreadGroupCountY, UINT ThreadGroupCountZ) = 0;
  virtual void DispatchIndirect(Buffer* pBufferForArgs, UINT AlignedByteOffsetForArgs) = 0;

  // Clears
  virtual void ClearRenderTargetView(RenderTargetView* pRenderTargetView, const FLOAT ColorRGBA[4]) = 0;
  virtual void ClearDepthStencilView(DepthStencilView* pDepthStencilView, UINT ClearFlags, FLOAT Depth,
                                     UINT8 Stencil) = 0;
  virtual void ClearUnorderedAccessViewUint(UnorderedAccessView* pUnorderedAccessView, const UINT Values[4]) = 0;
  virtual void ClearUnorderedAccessViewFloat(UnorderedAccessView* pUnorderedAccessView, const FLOAT Values[4]) = 0;

  // Resource access
  virtual HRESULT Map(Resource* pResource, UINT Subresource, MAP MapType, UINT MapFlags,
                      MAPPED_SUBRESOURCE* pMappedResource) = 0;
  virtual void Unmap(Resource* pResource, UINT Subresource) = 0;
  virtual void UpdateSubresource(Resource* pDstResource, UINT DstSubresource, const BOX* pDstBox,
                                 const void* pSrcData, UINT SrcRowPitch, UINT SrcDepthPitch) = 0;
  virtual void CopyResource(Resource* pDstResource, Resource* pSrcResource) = 0;
  virtual void CopySubresourceRegion(Resource* pDstResource, UINT DstSubresource, UINT DstX, UINT DstY, UINT DstZ,
                                     Resource* pSrcResource, UINT SrcSubresource, const BOX* pSrcBox) = 0;
  virtual void ResolveSubresource(Resource* pDstResource, UINT DstSubresource, Resource* pSrcResource,
                                  UINT SrcSubresource, DXGI_FORMAT Format) = 0;
  // Writes the hidden counter of an append/counter UAV as a UINT at DstAlignedByteOffset.
  virtual void CopyStructureCount(Buffer* pDstBuffer, UINT DstAlignedByteOffset,
                                  UnorderedAccessView* pSrcView) = 0;
  // Fills the view's mip levels below its most detailed one, each the 2x2 box
  // filter of the level above (2x2x2 for 3D textures); the resource needs
  // RESOURCE_MISC_GENERATE_MIPS.
  virtual void GenerateMips(ShaderResourceView* pShaderResourceView) = 0;
  // The most detailed mip level shader-resource views of the texture may sample
  // (texture_misc.cpp). Every SRV of pResource samples with its LOD clamped to at
  // least MinLOD; levels below it are not accessed, and a view whose levels all lie
  // below it reads 0. Fractional values blend as a sampler's MinLOD does where the
  // device has VK_EXT_image_view_min_lod; elsewhere the clamp is MinLOD rounded up
  // and explicit LODs count from it (docs/API_COVERAGE.md, Notes). The texture
  // needs RESOURCE_MISC_RESOURCE_CLAMP; MinLOD lies in [0, MipLevels].
  virtual void SetResourceMinLOD(Resource* pResource, FLOAT MinLOD) = 0;
  // What SetResourceMinLOD last set (0 for a new resource).
  virtual FLOAT GetResourceMinLOD(Resource* pResource) = 0;

  // Queries
  virtual void Begin(Asynchronous* pAsync) = 0;
  virtual void End(Asynchronous* pAsync) = 0;
  virtual HRESULT GetData(Asynchronous* pAsync, void* pData, UINT DataSize, UINT GetDataFlags) = 0;
  // While a predicate is set, Draw*, Dispatch*, Clear*, Copy*, UpdateSubresource,
  // ResolveSubresource and GenerateMips are skipped when its result equals
  // PredicateValue. The result is read when SetPredication is called, waiting
  // for it unless the predicate has QUERY_MISC_PREDICATEHINT (then rendering
  // goes ahead while it is unknown).
  virtual void SetPredication(Predicate* pPredicate, BOOL PredicateValue) = 0;
  virtual void GetPredication(Predicate** ppPredicate, BOOL* pPredicateValue) = 0;

  virtual void ClearState() = 0;
  virtual void Flush() = 0;
  // DEVICE_CONTEXT_IMMEDIATE or _DEFERRED; no context flags (D3D11 defines none for 11.0).
  virtual DEVICE_CONTEXT_TYPE GetType() = 0;
  virtual UINT GetContextFlags() = 0;

  // Immediate context only: runs the list's commands from the default state (a
  // list inherits nothing); afterwards the context's state is what it was
  // before (RestoreContextState TRUE) or the default (FALSE, as ClearState).
  virtual void ExecuteCommandList(CommandList* pCommandList, BOOL RestoreContextState) = 0;
  // Deferred contexts only (DXGI_ERROR_INVALID_CALL on the immediate one): the
  // commands recorded since the last call; the deferred context keeps its state
  // for what it records next (RestoreDeferredContextState TRUE) or returns to
  // the default state (FALSE).
  virtual HRESULT FinishCommandList(BOOL RestoreDeferredContextState, CommandList** ppCommandList) = 0;

  // ID3DUserDefinedAnnotation: named regions and markers for debuggers and traces
  // (rhi/trace.h). The Vulkan context emits debug-utils labels when
  // VK_EXT_debug_utils is enabled (the validation layer is on), else nothing.
  virtual void BeginEvent(const char* /*name*/) {}
  virtual void EndEvent() {}
  virtual void SetMarker(const char* /*name*/) {}
};

// ---------------------------------------------------------------------------
// The device

class Device : public Unknown {
 public:
  virtual HRESULT CreateBuffer(const BUFFER_DESC* pDesc, const SUBRESOURCE_DATA* pInitialData,
                               Buffer** ppBuffer) = 0;
  virtual HRESULT CreateTexture1D(const TEXTURE1D_DESC* pDesc, const SUBRESOURCE_DATA* pInitialData,
                                  Texture1D** ppTexture1D) = 0;
  virtual HRESULT CreateTexture2D(const TEXTURE2D_DESC* pDesc, const SUBRESOURCE_DATA* pInitialData,
                                  Texture2D** ppTexture2D) = 0;
  // Volume textures: SRVs (TEXTURE3D), RTVs of W-slice ranges (TEXTURE3D: each W slice a
  // render-target array slice) and UAVs (TEXTURE3D, every W slice of a mip; see views.cpp).
  virtual HRESULT CreateTexture3D(const TEXTURE3D_DESC* pDesc, const SUBRESOURCE_DATA* pInitialData,
                                  Texture3D** ppTexture3D) = 0;

  virtual HRESULT CreateShaderResourceView(Resource* pResource, const SHADER_RESOURCE_VIEW_DESC* pDesc,
                                           ShaderResourceView** ppSRView) = 0;
  virtual HRESULT CreateUnorderedAccessView(Resource* pResource, const UNORDERED_ACCESS_VIEW_DESC* pDesc,
                                            UnorderedAccessView** ppUAView) = 0;
  virtual HRESULT CreateRenderTargetView(Resource* pResource, const RENDER_TARGET_VIEW_DESC* pDesc,
                                         RenderTargetView** ppRTView) = 0;
  virtual HRESULT CreateDepthStencilView(Resource* pResource, const DEPTH_STENCIL_VIEW_DESC* pDesc,
                                         DepthStencilView** ppDepthStencilView) = 0;

  // pShaderBytecodeWithInputSignature: the SPIR-V of the vertex shader whose
  // input semantics the layout is matched against.
  virtual HRESULT CreateInputLayout(const INPUT_ELEMENT_DESC* pInputElementDescs, UINT NumElements,
                                    const void* pShaderBytecodeWithInputSignature, SIZE_T BytecodeLength,
                                    InputLayout** ppInputLayout) = 0;

  // Bytecode is SPIR-V (4-byte aligned words).
  virtual HRESULT CreateVertexShader(const void* pShaderBytecode, SIZE_T BytecodeLength,
                                     ClassLinkage* pClassLinkage, VertexShader** ppVertexShader) = 0;
  virtual HRESULT CreateHullShader(const void* pShaderBytecode, SIZE_T BytecodeLength, ClassLinkage* pClassLinkage,
                                   HullShader** ppHullShader) = 0;
  virtual HRESULT CreateDomainShader(const void* pShaderBytecode, SIZE_T BytecodeLength,
                                     ClassLinkage* pClassLinkage, DomainShader** ppDomainShader) = 0;
  virtual HRESULT CreateGeometryShader(const void* pShaderBytecode, SIZE_T BytecodeLength,
                                       ClassLinkage* pClassLinkage, GeometryShader** ppGeometryShader) = 0;
  // Stream output from a geometry shader, or from a vertex shader's bytecode
  // (D3D11 accepts VS bytecode here for VS-only stream output).
  virtual HRESULT CreateGeometryShaderWithStreamOutput(const void* pShaderBytecode, SIZE_T BytecodeLength,
                                                       const SO_DECLARATION_ENTRY* pSODeclaration, UINT NumEntries,
                                                       const UINT* pBufferStrides, UINT NumStrides,
                                                       UINT RasterizedStream, ClassLinkage* pClassLinkage,
                                                       GeometryShader** ppGeometryShader) = 0;
  virtual HRESULT CreatePixelShader(const void* pShaderBytecode, SIZE_T BytecodeLength, ClassLinkage* pClassLinkage,
                                    PixelShader** ppPixelShader) = 0;
  virtual HRESULT CreateComputeShader(const void* pShaderBytecode, SIZE_T BytecodeLength,
                                      ClassLinkage* pClassLinkage, ComputeShader** ppComputeShader) = 0;

  // Identical descriptions return the same object (with a new reference).
  virtual HRESULT CreateBlendState(const BLEND_DESC* pBlendStateDesc, BlendState** ppBlendState) = 0;
  virtual HRESULT CreateDepthStencilState(const DEPTH_STENCIL_DESC* pDepthStencilDesc,
                                          DepthStencilState** ppDepthStencilState) = 0;
  virtual HRESULT CreateRasterizerState(const RASTERIZER_DESC* pRasterizerDesc,
                                        RasterizerState** ppRasterizerState) = 0;
  virtual HRESULT CreateSamplerState(const SAMPLER_DESC* pSamplerDesc, SamplerState** ppSamplerState) = 0;

  virtual HRESULT CreateQuery(const QUERY_DESC* pQueryDesc, Query** ppQuery) = 0;
  // QUERY_OCCLUSION_PREDICATE or QUERY_SO_OVERFLOW_PREDICATE[_STREAMn].
  virtual HRESULT CreatePredicate(const QUERY_DESC* pPredicateDesc, Predicate** ppPredicate) = 0;

  // *pNumQualityLevels: 1 when a render target (or depth-stencil, for depth
  // formats) of Format may have SampleCount samples, else 0 (D3D11's answer for
  // an unsupported combination). Quality must then be 0 or
  // STANDARD_MULTISAMPLE_PATTERN. E_INVALIDARG for an unknown or typeless format.
  virtual HRESULT CheckMultisampleQualityLevels(DXGI_FORMAT Format, UINT SampleCount, UINT* pNumQualityLevels) = 0;

  virtual void GetImmediateContext(DeviceContext** ppImmediateContext) = 0;
  // A context that records into command lists, usable on another thread
  // (deferred_context.cpp). ContextFlags must be 0.
  virtual HRESULT CreateDeferredContext(UINT ContextFlags, DeviceContext** ppDeferredContext) = 0;

  // Queries of the device (device_queries.cpp).
  // Feature level 11_0, on every Vulkan 1.3 device the backend accepts.
  virtual D3D_FEATURE_LEVEL GetFeatureLevel() = 0;
  // CREATE_DEVICE_DEBUG when DEVICE_OPTIONS::EnableValidation (the debug layer's counterpart) is on.
  virtual UINT GetCreationFlags() = 0;
  // S_OK, or DXGI_ERROR_DEVICE_REMOVED once Vulkan reported VK_ERROR_DEVICE_LOST
  // (waits then return instead of hanging).
  virtual HRESULT GetDeviceRemovedReason() = 0;
  // RaiseFlags: 0 or RAISE_FLAG_DRIVER_INTERNAL_ERROR, kept and returned; no
  // exception is ever raised (device loss goes through GetDeviceRemovedReason).
  virtual HRESULT SetExceptionMode(UINT RaiseFlags) = 0;
  virtual UINT GetExceptionMode() = 0;
  // FORMAT_SUPPORT_* bits D3D11 defines for Format that this device has; E_FAIL
  // (and 0) for a format it cannot use at all.
  virtual HRESULT CheckFormatSupport(DXGI_FORMAT Format, UINT* pFormatSupport) = 0;
  // FEATURE_THREADING, _DOUBLES, _FORMAT_SUPPORT, _FORMAT_SUPPORT2 and
  // _D3D10_X_HARDWARE_OPTIONS; E_INVALIDARG for another feature or a size that
  // is not its struct's.
  virtual HRESULT CheckFeatureSupport(FEATURE Feature, void* pFeatureSupportData, UINT FeatureSupportDataSize) = 0;

  // What Vulkan cannot provide: these exist and refuse (device_queries.cpp).
  // Dynamic shader linkage has no SPIR-V counterpart: E_NOTIMPL.
  virtual HRESULT CreateClassLinkage(ClassLinkage** ppLinkage) = 0;
  // No device-dependent counters: CheckCounterInfo reports none, CreateCounter
  // returns DXGI_ERROR_UNSUPPORTED and CheckCounter E_INVALIDARG, as D3D11 does
  // for a counter the device lacks.
  virtual void CheckCounterInfo(COUNTER_INFO* pCounterInfo) = 0;
  virtual HRESULT CreateCounter(const COUNTER_DESC* pCounterDesc, Counter** ppCounter) = 0;
  virtual HRESULT CheckCounter(const COUNTER_DESC* pDesc, COUNTER_TYPE* pType, UINT* pActiveCounters, LPSTR szName,
                               UINT* pNameLength, LPSTR szUnits, UINT* pUnitsLength, LPSTR szDescription,
                               UINT* pDescriptionLength) = 0;
  // No resource is shared across processes (RESOURCE_MISC_SHARED is not
  // accepted), so no handle names one: E_INVALIDARG, as for a bad handle.
  virtual HRESULT OpenSharedResource(HANDLE hResource, REFIID ReturnedInterface, void** ppResource) = 0;

  // Private data (D3D11's semantics and HRESULTs). WKPDID_D3DDebugObjectName
  // also names the VkDevice (VK_EXT_debug_utils, with the validation layer).
  virtual HRESULT GetPrivateData(REFGUID guid, UINT* pDataSize, void* pData) = 0;
  virtual HRESULT SetPrivateData(REFGUID guid, UINT DataSize, const void* pData) = 0;
  virtual HRESULT SetPrivateDataInterface(REFGUID guid, const Unknown* pData) = 0;

  // Not in D3D11: the Vulkan physical device's name ("llvmpipe (LLVM 15.0.6, 256 bits)").
  virtual const char* GetAdapterName() = 0;
};

// ---------------------------------------------------------------------------
// Creating a device

enum MESSAGE_SEVERITY : UINT {
  MESSAGE_SEVERITY_CORRUPTION = 0,
  MESSAGE_SEVERITY_ERROR = 1,
  MESSAGE_SEVERITY_WARNING = 2,
  MESSAGE_SEVERITY_INFO = 3,
  MESSAGE_SEVERITY_MESSAGE = 4,
};

enum MESSAGE_CATEGORY : UINT {
  MESSAGE_CATEGORY_STATE_CREATION = 6,
  MESSAGE_CATEGORY_STATE_SETTING = 7,
  MESSAGE_CATEGORY_EXECUTION = 9,
  // Not in D3D11: a message of the Khronos validation layer.
  MESSAGE_CATEGORY_VULKAN_VALIDATION = 100,
};

using MessageCallback = std::function<void(MESSAGE_CATEGORY, MESSAGE_SEVERITY, const char* description)>;

struct DEVICE_OPTIONS {
  // A substring of the Vulkan device name to pick ("llvmpipe", "NVIDIA"); null
  // means the RHI_DEVICE environment variable, else lavapipe, else the first device.
  const char* AdapterName = nullptr;
  // Enables the Khronos validation layer (also on when RHI_VALIDATION=1 or in debug builds).
  BOOL EnableValidation = FALSE;
  // DrawAuto through vkCmdDrawIndirectByteCountEXT instead of the default
  // GPU-written indirect arguments (also on when RHI_NATIVE_DRAW_AUTO=1).
  BOOL NativeDrawAuto = FALSE;
  // Receives every refusal reason (the D3D11 debug layer's role) and every
  // validation-layer message. Without one, errors go to stderr.
  MessageCallback OnMessage;
  // Extra Vulkan instance extensions, e.g. the surface extensions a window system
  // needs for rhi/swap_chain.h (glfwGetRequiredInstanceExtensions).
  const char* const* InstanceExtensions = nullptr;
  UINT InstanceExtensionCount = 0;
};

HRESULT CreateDevice(const DEVICE_OPTIONS* pOptions, Device** ppDevice, DeviceContext** ppImmediateContext);

}  // namespace rhi
