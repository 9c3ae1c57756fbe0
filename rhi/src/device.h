// The D3D11 device over Vulkan, and the base of every device child.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include "gpu.h"
#include "host_slices.h"
#include "private_data.h"
#include "rhi/rhi.h"

namespace rhi::vk {

class ContextImpl;
class PipelineCache;
struct ObjectCaches;

class DeviceImpl final : public Device {
 public:
  static HRESULT Create(const DEVICE_OPTIONS& options, DeviceImpl** device);
  ~DeviceImpl() override;

  HRESULT CreateBuffer(const BUFFER_DESC* pDesc, const SUBRESOURCE_DATA* pInitialData, Buffer** ppBuffer) override;
  HRESULT CreateTexture1D(const TEXTURE1D_DESC* pDesc, const SUBRESOURCE_DATA* pInitialData,
                          Texture1D** ppTexture1D) override;
  HRESULT CreateTexture2D(const TEXTURE2D_DESC* pDesc, const SUBRESOURCE_DATA* pInitialData,
                          Texture2D** ppTexture2D) override;
  HRESULT CreateTexture3D(const TEXTURE3D_DESC* pDesc, const SUBRESOURCE_DATA* pInitialData,
                          Texture3D** ppTexture3D) override;
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
  HRESULT CreatePredicate(const QUERY_DESC* pPredicateDesc, Predicate** ppPredicate) override;  // predication.cpp
  HRESULT CheckMultisampleQualityLevels(DXGI_FORMAT Format, UINT SampleCount, UINT* pNumQualityLevels) override;
  void GetImmediateContext(DeviceContext** ppImmediateContext) override;
  HRESULT CreateDeferredContext(UINT ContextFlags, DeviceContext** ppDeferredContext) override;  // deferred_context.cpp
  // device_queries.cpp
  D3D_FEATURE_LEVEL GetFeatureLevel() override { return D3D_FEATURE_LEVEL_11_0; }
  UINT GetCreationFlags() override;
  HRESULT GetDeviceRemovedReason() override;
  HRESULT SetExceptionMode(UINT RaiseFlags) override;
  UINT GetExceptionMode() override { return exceptionMode_; }
  HRESULT CheckFormatSupport(DXGI_FORMAT Format, UINT* pFormatSupport) override;
  HRESULT CheckFeatureSupport(FEATURE Feature, void* pFeatureSupportData, UINT FeatureSupportDataSize) override;
  HRESULT CreateClassLinkage(ClassLinkage** ppLinkage) override;
  void CheckCounterInfo(COUNTER_INFO* pCounterInfo) override;
  HRESULT CreateCounter(const COUNTER_DESC* pCounterDesc, Counter** ppCounter) override;
  HRESULT CheckCounter(const COUNTER_DESC* pDesc, COUNTER_TYPE* pType, UINT* pActiveCounters, LPSTR szName,
                       UINT* pNameLength, LPSTR szUnits, UINT* pUnitsLength, LPSTR szDescription,
                       UINT* pDescriptionLength) override;
  HRESULT OpenSharedResource(HANDLE hResource, REFIID ReturnedInterface, void** ppResource) override;
  // private_data.cpp
  HRESULT GetPrivateData(REFGUID guid, UINT* pDataSize, void* pData) override;
  HRESULT SetPrivateData(REFGUID guid, UINT DataSize, const void* pData) override;
  HRESULT SetPrivateDataInterface(REFGUID guid, const Unknown* pData) override;
  const char* GetAdapterName() override { return gpu_->AdapterName().c_str(); }

  Gpu& gpu() { return *gpu_; }
  HostSliceAllocator& hostSlices() { return *hostSlices_; }
  ContextImpl& context() { return *context_; }
  PipelineCache& pipelines() { return *pipelines_; }
  ObjectCaches& caches() { return *caches_; }
  // Ids of object contents (pipeline keys): unique for the device's lifetime.
  uint64_t NextContentId() { return ++lastContentId_; }
  // Held by creation calls that record into the immediate context (initial
  // data, image layouts), so that creation from many threads is safe.
  std::mutex& creationRecordingMutex() { return creationRecordingMutex_; }

 private:
  DeviceImpl() = default;
  template <class Impl, class Interface, class Desc>
  HRESULT CreateDeduplicated(const Desc* desc, Interface** out);

  std::unique_ptr<Gpu> gpu_;
  std::unique_ptr<HostSliceAllocator> hostSlices_;
  std::unique_ptr<PipelineCache> pipelines_;
  std::unique_ptr<ContextImpl> context_;
  UINT exceptionMode_ = 0;  // SetExceptionMode
  PrivateDataStore privateData_;
  std::unique_ptr<ObjectCaches> caches_;
  std::atomic<uint64_t> lastContentId_{0};
  std::mutex creationRecordingMutex_;
};

// What the context's bindings hold on an object: it stays alive while bound,
// as in D3D11, without the binding keeping the device alive. Binding and
// unbinding are non-virtual counter updates: the context does them on every
// binding call.
class Bindable {
 public:
  void Bind() { counts_.fetch_add(kOneBinding, std::memory_order_relaxed); }
  void Unbind() {
    if (counts_.fetch_sub(kOneBinding, std::memory_order_acq_rel) == kOneBinding) Destroy();
  }

 protected:
  ~Bindable() = default;
  // Deletes the object once neither the application nor a binding holds it.
  virtual void Destroy() = 0;

  static constexpr uint64_t kOneBinding = uint64_t(1) << 32;
  static UINT References(uint64_t counts) { return static_cast<UINT>(counts); }
  // The application's references (low 32 bits) and the context's bindings
  // (high 32 bits) in one atomic, as the device is free-threaded: exactly one
  // thread sees the pair reach zero, and that one deletes the object.
  std::atomic<uint64_t> counts_{1};
};

// D3D11's lifetime rules for device children: an object lives while the
// application holds a reference or the context binds it, and the application's
// references keep the device alive. Bindings do not, so objects bound when the
// device goes are released by the device's own ClearState, and bound objects
// never form reference cycles with the device.
template <class Interface>
class DeviceChildImpl : public Interface, public Bindable {
 public:
  explicit DeviceChildImpl(DeviceImpl* device) : device_(device) {
    device_->AddRef();  // for the creator's reference
  }
  UINT AddRef() override {
    const uint64_t before = counts_.fetch_add(1, std::memory_order_relaxed);
    if (References(before) == 0) device_->AddRef();
    return References(before) + 1;
  }
  UINT Release() override {
    DeviceImpl* device = device_;  // read first: another thread may delete the object once the count drops
    const uint64_t before = counts_.fetch_sub(1, std::memory_order_acq_rel);
    if (References(before) == 1) {
      if (before == 1) delete this;
      device->Release();
    }
    return References(before) - 1;
  }
  // AddRef, unless the object is already being deleted (no reference and no
  // binding left): for caches that hold objects weakly.
  bool TryAddRef() {
    uint64_t counts = counts_.load(std::memory_order_relaxed);
    do {
      if (counts == 0) return false;
    } while (!counts_.compare_exchange_weak(counts, counts + 1, std::memory_order_acquire, std::memory_order_relaxed));
    if (References(counts) == 0) device_->AddRef();
    return true;
  }
  void GetDevice(Device** ppDevice) override {
    device_->AddRef();
    *ppDevice = device_;
  }
  DeviceImpl& device() const { return *device_; }
  Gpu& gpu() const { return device_->gpu(); }

 protected:
  void Destroy() override { delete this; }

 private:
  DeviceImpl* device_;
};

// A context binding (see Bindable).
template <class T>
class Bound {
 public:
  Bound() = default;
  Bound(T* object) : object_(object) {
    if (object_) object_->Bind();
  }
  Bound(const Bound& other) : Bound(other.object_) {}
  Bound(Bound&& other) noexcept : object_(std::exchange(other.object_, nullptr)) {}
  Bound& operator=(const Bound& other) { return *this = other.object_; }
  Bound& operator=(Bound&& other) noexcept {
    if (this != &other) {
      Reset();
      object_ = std::exchange(other.object_, nullptr);
    }
    return *this;
  }
  // Binds `object` in place of the current one; rebinding the same object is free.
  Bound& operator=(T* object) {
    if (object == object_) return *this;
    if (object) object->Bind();
    Reset();
    object_ = object;
    return *this;
  }
  ~Bound() { Reset(); }
  void Reset() {
    if (T* object = std::exchange(object_, nullptr)) object->Unbind();
  }
  T* Get() const { return object_; }
  T* operator->() const { return object_; }
  T& operator*() const { return *object_; }
  explicit operator bool() const { return object_ != nullptr; }

 private:
  T* object_ = nullptr;
};

}  // namespace rhi::vk
