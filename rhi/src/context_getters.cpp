// The context's getters: what the setters bound, each object returned with a
// reference the caller releases, as D3D11's getters do (imgui_impl_dx11 saves
// and restores the whole pipeline state through them).
#include <algorithm>

#include "context.h"
#include "resources.h"
#include "shaders.h"
#include "state_objects.h"
#include "views.h"

namespace rhi::vk {

namespace {

// The bound object as its interface, with a new reference; null stays null.
template <class Interface, class Impl>
Interface* Referenced(Impl* object) {
  if (!object) return nullptr;
  object->AddRef();
  return object;
}

// Copies `count` slots from `start`; slots past the end of `slots` read as empty.
template <class Interface, class Slots>
void GetSlots(const Slots& slots, UINT start, UINT count, Interface** out) {
  if (!out) return;
  for (UINT i = 0; i < count; ++i)
    out[i] = start + i < slots.size() ? Referenced<Interface>(slots[start + i].Get()) : nullptr;
}

// D3D11's RSGetViewports / RSGetScissorRects: the count alone, or `*count`
// entries with zeros past the bound ones.
template <class T>
void GetRects(const std::vector<T>& bound, UINT* count, T* out) {
  if (!count) return;
  if (!out) {
    *count = static_cast<UINT>(bound.size());
    return;
  }
  for (UINT i = 0; i < *count; ++i) out[i] = i < bound.size() ? bound[i] : T{};
}

}  // namespace

void ContextImpl::IAGetInputLayout(InputLayout** ppInputLayout) {
  if (ppInputLayout) *ppInputLayout = Referenced<InputLayout>(inputLayout_.Get());
}

void ContextImpl::IAGetVertexBuffers(UINT StartSlot, UINT NumBuffers, Buffer** ppVertexBuffers, UINT* pStrides,
                                     UINT* pOffsets) {
  for (UINT i = 0; i < NumBuffers; ++i) {
    const bool inRange = StartSlot + i < vertexBuffers_.size();
    const VertexBufferBinding empty;
    const VertexBufferBinding& binding = inRange ? vertexBuffers_[StartSlot + i] : empty;
    if (ppVertexBuffers) ppVertexBuffers[i] = Referenced<Buffer>(binding.buffer.Get());
    if (pStrides) pStrides[i] = binding.stride;
    if (pOffsets) pOffsets[i] = binding.offset;
  }
}

void ContextImpl::IAGetIndexBuffer(Buffer** pIndexBuffer, DXGI_FORMAT* Format, UINT* Offset) {
  if (pIndexBuffer) *pIndexBuffer = Referenced<Buffer>(indexBuffer_.buffer.Get());
  if (Format) *Format = indexBuffer_.format;
  if (Offset) *Offset = indexBuffer_.offset;
}

void ContextImpl::IAGetPrimitiveTopology(PRIMITIVE_TOPOLOGY* pTopology) {
  if (pTopology) *pTopology = topology_;
}

// The stage's shader object was bound as a Bindable; each stage binds one interface type.
#define RHI_GET_SHADER(Prefix, Stage, Interface)                                                                \
  void ContextImpl::Prefix##GetShader(Interface** ppShader, ClassInstance**, UINT* pNumClassInstances) {       \
    if (pNumClassInstances) *pNumClassInstances = 0;                                                            \
    if (!ppShader) return;                                                                                      \
    Bindable* bound = stages_[static_cast<uint32_t>(ShaderStage::Stage)].shaderObject.Get();                   \
    *ppShader = Referenced<Interface>(static_cast<ShaderObject<Interface>*>(bound));                            \
  }
RHI_GET_SHADER(VS, Vertex, VertexShader)
RHI_GET_SHADER(HS, Hull, HullShader)
RHI_GET_SHADER(DS, Domain, DomainShader)
RHI_GET_SHADER(GS, Geometry, GeometryShader)
RHI_GET_SHADER(PS, Pixel, PixelShader)
RHI_GET_SHADER(CS, Compute, ComputeShader)
#undef RHI_GET_SHADER

void ContextImpl::GetConstantBuffers(ShaderStage stage, UINT start, UINT count, Buffer** buffers) {
  GetSlots(stages_[static_cast<uint32_t>(stage)].constantBuffers, start, count, buffers);
}

void ContextImpl::GetShaderResources(ShaderStage stage, UINT start, UINT count, ShaderResourceView** views) {
  GetSlots(stages_[static_cast<uint32_t>(stage)].shaderResources, start, count, views);
}

void ContextImpl::GetSamplers(ShaderStage stage, UINT start, UINT count, SamplerState** samplers) {
  GetSlots(stages_[static_cast<uint32_t>(stage)].samplers, start, count, samplers);
}

void ContextImpl::CSGetUnorderedAccessViews(UINT StartSlot, UINT NumUAVs, UnorderedAccessView** ppUnorderedAccessViews) {
  GetSlots(computeUavs_, StartSlot, NumUAVs, ppUnorderedAccessViews);
}

void ContextImpl::RSGetState(RasterizerState** ppRasterizerState) {
  if (ppRasterizerState) *ppRasterizerState = Referenced<RasterizerState>(rasterizer_.Get());
}

void ContextImpl::RSGetViewports(UINT* pNumViewports, VIEWPORT* pViewports) {
  GetRects(viewports_, pNumViewports, pViewports);
}

void ContextImpl::RSGetScissorRects(UINT* pNumRects, RECT* pRects) { GetRects(scissors_, pNumRects, pRects); }

void ContextImpl::OMGetRenderTargets(UINT NumViews, RenderTargetView** ppRenderTargetViews,
                                     DepthStencilView** ppDepthStencilView) {
  GetSlots(renderTargets_, 0, NumViews, ppRenderTargetViews);
  if (ppDepthStencilView) *ppDepthStencilView = Referenced<DepthStencilView>(depthStencil_.Get());
}

void ContextImpl::OMGetBlendState(BlendState** ppBlendState, FLOAT BlendFactor[4], UINT* pSampleMask) {
  if (ppBlendState) *ppBlendState = Referenced<BlendState>(blendState_.Get());
  if (BlendFactor) std::copy(blendFactor_.begin(), blendFactor_.end(), BlendFactor);
  if (pSampleMask) *pSampleMask = sampleMask_;
}

void ContextImpl::OMGetDepthStencilState(DepthStencilState** ppDepthStencilState, UINT* pStencilRef) {
  if (ppDepthStencilState) *ppDepthStencilState = Referenced<DepthStencilState>(depthStencilState_.Get());
  if (pStencilRef) *pStencilRef = stencilRef_;
}

}  // namespace rhi::vk
