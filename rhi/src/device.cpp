#include "device.h"

#include <cstring>

#include "context.h"
#include "pipelines.h"
#include "queries.h"
#include "resources.h"
#include "shaders.h"
#include "state_objects.h"
#include "states/formats.h"
#include "views.h"

namespace rhi {

HRESULT CreateDevice(const DEVICE_OPTIONS* pOptions, Device** ppDevice, DeviceContext** ppImmediateContext) {
  DEVICE_OPTIONS defaults;
  vk::DeviceImpl* device = nullptr;
  HRESULT hr = vk::DeviceImpl::Create(pOptions ? *pOptions : defaults, &device);
  if (FAILED(hr)) return hr;
  if (ppImmediateContext) device->GetImmediateContext(ppImmediateContext);
  if (ppDevice)
    *ppDevice = device;
  else
    device->Release();
  return S_OK;
}

}  // namespace rhi

namespace rhi::vk {

HRESULT DeviceImpl::Create(const DEVICE_OPTIONS& options, DeviceImpl** out) {
  ComPtr<DeviceImpl> device;
  device.Attach(new DeviceImpl());
  if (HRESULT hr = Gpu::Create(options, &device->gpu_); FAILED(hr)) return hr;
  device->hostSlices_ = std::make_unique<HostSliceAllocator>(*device->gpu_);
  device->pipelines_ = std::make_unique<PipelineCache>(*device->gpu_);
  device->caches_ = std::make_unique<ObjectCaches>();
  device->context_ = std::make_unique<ContextImpl>(device.Get());
  *out = device.Detach();
  return S_OK;
}

DeviceImpl::~DeviceImpl() {
  // Bound objects release their references to this device while the context
  // is cleared, so clear it before anything else goes.
  context_->ClearState();
  context_->Flush();
  gpu_->WaitIdle();
  context_.reset();
  pipelines_.reset();
  gpu_->WaitIdle();
  hostSlices_.reset();
  gpu_.reset();
}

void DeviceImpl::GetImmediateContext(DeviceContext** ppImmediateContext) {
  context_->AddRef();
  *ppImmediateContext = context_.get();
}

// ---------------------------------------------------------------------------
// Resources and views

HRESULT DeviceImpl::CreateBuffer(const BUFFER_DESC* pDesc, const SUBRESOURCE_DATA* pInitialData, Buffer** ppBuffer) {
  if (!pDesc) return gpu_->Refuse("CreateBuffer: pDesc is NULL");
  BufferImpl* buffer = nullptr;
  HRESULT hr = BufferImpl::Create(this, *pDesc, pInitialData, &buffer);
  if (SUCCEEDED(hr)) *ppBuffer = buffer;
  return hr;
}

template <class Impl, class Desc>
static HRESULT CreateTexture(DeviceImpl* device, const Desc& desc, const TextureShape& shape,
                             const SUBRESOURCE_DATA* initialData, Impl** out) {
  ComPtr<Impl> texture;
  texture.Attach(new Impl(device, desc));
  if (HRESULT hr = texture->Initialize(*device, shape, initialData); FAILED(hr)) return hr;
  *out = texture.Detach();
  return S_OK;
}

HRESULT DeviceImpl::CreateTexture1D(const TEXTURE1D_DESC* pDesc, const SUBRESOURCE_DATA* pInitialData,
                                    Texture1D** ppTexture1D) {
  if (!pDesc) return gpu_->Refuse("CreateTexture1D: pDesc is NULL");
  TextureShape shape{RESOURCE_DIMENSION_TEXTURE1D, pDesc->Width, 1, pDesc->MipLevels, pDesc->ArraySize, 1,
                     pDesc->Format, pDesc->Usage, pDesc->BindFlags, pDesc->CPUAccessFlags, pDesc->MiscFlags};
  Texture1DImpl* texture = nullptr;
  HRESULT hr = CreateTexture(this, *pDesc, shape, pInitialData, &texture);
  if (SUCCEEDED(hr)) *ppTexture1D = texture;
  return hr;
}

HRESULT DeviceImpl::CreateTexture2D(const TEXTURE2D_DESC* pDesc, const SUBRESOURCE_DATA* pInitialData,
                                    Texture2D** ppTexture2D) {
  if (!pDesc) return gpu_->Refuse("CreateTexture2D: pDesc is NULL");
  TextureShape shape{RESOURCE_DIMENSION_TEXTURE2D, pDesc->Width,          pDesc->Height,
                     pDesc->MipLevels,             pDesc->ArraySize,      pDesc->SampleDesc.Count,
                     pDesc->Format,                pDesc->Usage,          pDesc->BindFlags,
                     pDesc->CPUAccessFlags,        pDesc->MiscFlags,      pDesc->SampleDesc.Quality};
  Texture2DImpl* texture = nullptr;
  HRESULT hr = CreateTexture(this, *pDesc, shape, pInitialData, &texture);
  if (SUCCEEDED(hr)) *ppTexture2D = texture;
  return hr;
}

HRESULT DeviceImpl::CreateTexture3D(const TEXTURE3D_DESC* pDesc, const SUBRESOURCE_DATA* pInitialData,
                                    Texture3D** ppTexture3D) {
  if (!pDesc) return gpu_->Refuse("CreateTexture3D: pDesc is NULL");
  TextureShape shape{RESOURCE_DIMENSION_TEXTURE3D, pDesc->Width, pDesc->Height, pDesc->MipLevels, 1, 1,
                     pDesc->Format, pDesc->Usage, pDesc->BindFlags, pDesc->CPUAccessFlags, pDesc->MiscFlags};
  shape.depth = pDesc->Depth;
  Texture3DImpl* texture = nullptr;
  HRESULT hr = CreateTexture(this, *pDesc, shape, pInitialData, &texture);
  if (SUCCEEDED(hr)) *ppTexture3D = texture;
  return hr;
}

HRESULT DeviceImpl::CheckMultisampleQualityLevels(DXGI_FORMAT Format, UINT SampleCount, UINT* pNumQualityLevels) {
  if (!pNumQualityLevels) return gpu_->Refuse("CheckMultisampleQualityLevels: pNumQualityLevels is NULL");
  *pNumQualityLevels = 0;
  const auto* info = states::GetFormatInfo(Format);
  if (!info || info->kind == states::ComponentKind::Typeless)
    return gpu_->Refuse("CheckMultisampleQualityLevels: Format " + std::to_string(Format) +
                        " is not a typed format");
  if (SampleCount == 0 || SampleCount > MAX_MULTISAMPLE_SAMPLE_COUNT || (SampleCount & (SampleCount - 1))) return S_OK;
  // Vulkan has one pattern per count (the standard one): one quality level.
  if (TargetSampleCounts(*gpu_, Format) & SampleCount) *pNumQualityLevels = 1;
  return S_OK;
}

HRESULT DeviceImpl::CreateShaderResourceView(Resource* pResource, const SHADER_RESOURCE_VIEW_DESC* pDesc,
                                             ShaderResourceView** ppSRView) {
  return ShaderResourceViewImpl::Create(this, pResource, pDesc, ppSRView);
}

HRESULT DeviceImpl::CreateUnorderedAccessView(Resource* pResource, const UNORDERED_ACCESS_VIEW_DESC* pDesc,
                                              UnorderedAccessView** ppUAView) {
  return UnorderedAccessViewImpl::Create(this, pResource, pDesc, ppUAView);
}

HRESULT DeviceImpl::CreateRenderTargetView(Resource* pResource, const RENDER_TARGET_VIEW_DESC* pDesc,
                                           RenderTargetView** ppRTView) {
  return RenderTargetViewImpl::Create(this, pResource, pDesc, ppRTView);
}

HRESULT DeviceImpl::CreateDepthStencilView(Resource* pResource, const DEPTH_STENCIL_VIEW_DESC* pDesc,
                                           DepthStencilView** ppDepthStencilView) {
  return DepthStencilViewImpl::Create(this, pResource, pDesc, ppDepthStencilView);
}

// ---------------------------------------------------------------------------
// State objects

template <class Impl, class Interface, class Desc>
HRESULT DeviceImpl::CreateDeduplicated(const Desc* desc, Interface** out) {
  if (!desc) return gpu_->Refuse("Create*State: the description is NULL");
  if (std::string reason = states::Validate(*desc); !reason.empty()) return gpu_->Refuse(reason);
  // D3D11 deduplicates by the normalised desc, and GetDesc reports that form.
  const Desc normalized = states::Normalize(*desc);
  auto create = [&](uint64_t contentId, StateObject<Interface, Desc>** created) -> HRESULT {
    ComPtr<Impl> object;
    object.Attach(new Impl(this, normalized, contentId));
    if constexpr (std::is_same_v<Impl, SamplerStateImpl>) {
      if (HRESULT hr = object->Initialize(); FAILED(hr)) return hr;
    }
    *created = object.Detach();
    return S_OK;
  };
  StateObject<Interface, Desc>* object = nullptr;
  HRESULT hr = caches_->Of(&normalized).FindOrCreate(*this, normalized, create, &object);
  if (SUCCEEDED(hr)) *out = static_cast<Impl*>(object);
  return hr;
}

HRESULT DeviceImpl::CreateBlendState(const BLEND_DESC* pBlendStateDesc, BlendState** ppBlendState) {
  return CreateDeduplicated<BlendStateImpl>(pBlendStateDesc, ppBlendState);
}

HRESULT DeviceImpl::CreateDepthStencilState(const DEPTH_STENCIL_DESC* pDepthStencilDesc,
                                            DepthStencilState** ppDepthStencilState) {
  return CreateDeduplicated<DepthStencilStateImpl>(pDepthStencilDesc, ppDepthStencilState);
}

HRESULT DeviceImpl::CreateRasterizerState(const RASTERIZER_DESC* pRasterizerDesc,
                                          RasterizerState** ppRasterizerState) {
  return CreateDeduplicated<RasterizerStateImpl>(pRasterizerDesc, ppRasterizerState);
}

HRESULT DeviceImpl::CreateSamplerState(const SAMPLER_DESC* pSamplerDesc, SamplerState** ppSamplerState) {
  return CreateDeduplicated<SamplerStateImpl>(pSamplerDesc, ppSamplerState);
}

HRESULT DeviceImpl::CreateQuery(const QUERY_DESC* pQueryDesc, Query** ppQuery) {
  if (!pQueryDesc) return gpu_->Refuse("CreateQuery: pQueryDesc is NULL");
  QueryImpl* query = nullptr;
  HRESULT hr = QueryImpl::Create(this, *pQueryDesc, &query);
  if (SUCCEEDED(hr)) *ppQuery = query;
  return hr;
}

}  // namespace rhi::vk
