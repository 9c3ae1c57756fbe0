// The D3D11 device over Vulkan, and the base of every device child.
#pragma once

#include <memory>
#include <string>
#include <unordered_map>

#include "gpu.h"
#include "host_slices.h"
#include "rhi/rhi.h"

namespace rhi::vk {

class ContextImpl;
class PipelineCache;

class DeviceImpl final : public Device {
 public:
  static HRESULT Create(const DEVICE_OPTIONS& options, DeviceImpl** device);
  ~DeviceImpl() override;

  HRESULT CreateBuffer(const BUFFER_DESC* pDesc, const SUBRESOURCE_DATA* pInitialData, Buffer** ppBuffer) override;
  HRESULT CreateTexture1D(const TEXTURE1D_DESC* pDesc, const SUBRESOURCE_DATA* pInitialData,
                          Texture1D** ppTexture1D) override;
  HRESULT CreateTexture2D(const TEXTURE2D_DESC* pDesc, const SUBRESOURCE_DATA* pInitialData,
                          Texture2D** ppTexture2D) override;
  HRESULT CreateShaderResourceView(Resource* pResource, const SHADER_RESOURCE_VIEW_DESC* pDesc,
                                   ShaderResourceView** ppSRView) override;
  HRESULT CreateUnorderedAccessView(Resource* pResource, const UNORDERED_ACCESS_VIEW_DESC* pDesc,
                                    UnorderedAccessView** ppUAView) override;
  HRESULT CreateRenderTargetView(Resource* pResource, const RENDER_TARGET_VIEW_DESC* pDesc,
                                 RenderTargetView** ppRTView) override;
  HRESULT CreateDepthStencilView(Resource* pResource, const DEPTH_STENCIL_VIEW_DESC* pDesc,
                                 DepthStencilView** ppDepthStencilView) override;
  HRESULT CreateInputLayout(const INPUT_ELEMENT_DESC* pInputElementDescs, UINT NumElements,
                            const void* pShaderBytecodeWithInputSignature, SIZE_T BytecodeLength,
                            InputLayout** ppInputLayout) override;
  HRESULT CreateVertexShader(const void* pShaderBytecode, SIZE_T BytecodeLength, ClassLinkage* pClassLinkage,
                             VertexShader** ppVertexShader) override;
  HRESULT CreateHullShader(const void* pShaderBytecode, SIZE_T BytecodeLength, ClassLinkage* pClassLinkage,
                           HullShader** ppHullShader) override;
  HRESULT CreateDomainShader(const void* pShaderBytecode, SIZE_T BytecodeLength, ClassLinkage* pClassLinkage,
                             DomainShader** ppDomainShader) override;
  HRESULT CreateGeometryShader(const void* pShaderBytecode, SIZE_T BytecodeLength, ClassLinkage* pClassLinkage,
                               GeometryShader** ppGeometryShader) override;
  HRESULT CreateGeometryShaderWithStreamOutput(const void* pShaderBytecode, SIZE_T BytecodeLength,
                                               const SO_DECLARATION_ENTRY* pSODeclaration, UINT NumEntries,
                                               const UINT* pBufferStrides, UINT NumStrides, UINT RasterizedStream,
                                               ClassLinkage* pClassLinkage,
                                               GeometryShader** ppGeometryShader) override;
  HRESULT CreatePixelShader(const void* pShaderBytecode, SIZE_T BytecodeLength, ClassLinkage* pClassLinkage,
                            PixelShader** ppPixelShader) override;
  HRESULT CreateComputeShader(const void* pShaderBytecode, SIZE_T BytecodeLength, ClassLinkage* pClassLinkage,
                              ComputeShader** ppComputeShader) override;
  HRESULT CreateBlendState(const BLEND_DESC* pBlendStateDesc, BlendState** ppBlendState) override;
  HRESULT CreateDepthStencilState(const DEPTH_STENCIL_DESC* pDepthStencilDesc,
                                  DepthStencilState** ppDepthStencilState) override;
  HRESULT CreateRasterizerState(const RASTERIZER_DESC* pRasterizerDesc,
                                RasterizerState** ppRasterizerState) override;
  HRESULT CreateSamplerState(const SAMPLER_DESC* pSamplerDesc, SamplerState** ppSamplerState) override;
  HRESULT CreateQuery(const QUERY_DESC* pQueryDesc, Query** ppQuery) override;
  void GetImmediateContext(DeviceContext** ppImmediateContext) override;
  const char* GetAdapterName() override { return gpu_->AdapterName().c_str(); }

  Gpu& gpu() { return *gpu_; }
  HostSliceAllocator& hostSlices() { return *hostSlices_; }
  ContextImpl& context() { return *context_; }
  PipelineCache& pipelines() { return *pipelines_; }
  uint64_t NextSerial() { return ++objectSerial_; }

  // Deduplicated state objects forget themselves when their last reference goes.
  void ForgetState(DeviceChild* object);

 private:
  DeviceImpl() = default;
  template <class Impl, class Interface, class Desc>
  HRESULT CreateDeduplicated(const Desc* desc, Interface** out);

  std::unique_ptr<Gpu> gpu_;
  std::unique_ptr<HostSliceAllocator> hostSlices_;
  std::unique_ptr<PipelineCache> pipelines_;
  std::unique_ptr<ContextImpl> context_;
  uint64_t objectSerial_ = 0;
  // D3D11 returns the existing object for a desc identical to an earlier one.
  // Keyed by states::RawHash of the desc as given; values are weak.
  std::unordered_multimap<uint64_t, DeviceChild*> stateCache_;
};

// Unlike D3D11, a device child does not keep its device alive: the context's
// bindings hold references to children, and children holding the device would
// make every bound object a reference cycle. Release children before the device.
template <class Interface>
class DeviceChildImpl : public Interface {
 public:
  explicit DeviceChildImpl(DeviceImpl* device) : device_(device), serial_(device->NextSerial()) {}
  void GetDevice(Device** ppDevice) override {
    device_->AddRef();
    *ppDevice = device_;
  }
  DeviceImpl& device() const { return *device_; }
  Gpu& gpu() const { return device_->gpu(); }
  // Unique for the device's lifetime: pipeline keys use it instead of pointers.
  uint64_t serial() const { return serial_; }

 private:
  DeviceImpl* device_;
  uint64_t serial_;
};

}  // namespace rhi::vk
