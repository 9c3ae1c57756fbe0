// ID3D11Device's queries (format and feature support, creation flags,
// exception mode, removal) and the methods that refuse what Vulkan cannot
// provide (class linkage, counters, shared resources), as D3D11 refuses a
// feature the device lacks.
#include <string>

#include "device.h"
#include "resources.h"
#include "states/formats.h"

namespace rhi::vk {

namespace {

struct FormatFeatures {
  VkFormatFeatureFlags2 image = 0;   // optimal tiling
  VkFormatFeatureFlags2 buffer = 0;
};

FormatFeatures FeaturesOf(const Gpu& gpu, VkFormat format) {
  VkFormatProperties3 props3{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_3};
  VkFormatProperties2 props{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_2};
  props.pNext = &props3;
  vkGetPhysicalDeviceFormatProperties2(gpu.Physical(), format, &props);
  return {props3.optimalTilingFeatures, props3.bufferFeatures};
}

constexpr UINT kTextureDimensions = FORMAT_SUPPORT_TEXTURE1D | FORMAT_SUPPORT_TEXTURE2D | FORMAT_SUPPORT_TEXTURE3D |
                                    FORMAT_SUPPORT_TEXTURECUBE | FORMAT_SUPPORT_MIP | FORMAT_SUPPORT_CPU_LOCKABLE;

// The D3D11 uses of `info` (its bindFlags: what feature level 11_0 allows the
// format) that the Vulkan device also supports.
UINT FormatSupport(const Gpu& gpu, const states::FormatInfo& info) {
  const FormatFeatures vk = FeaturesOf(gpu, info.vkFormat);
  const bool integer = info.kind == states::ComponentKind::Uint || info.kind == states::ComponentKind::Sint;
  UINT support = 0;
  if (info.kind == states::ComponentKind::Typeless) {
    // A typeless format is storage whose views pick the type.
    if (vk.image & VK_FORMAT_FEATURE_2_TRANSFER_DST_BIT) support |= kTextureDimensions | FORMAT_SUPPORT_CAST_WITHIN_BIT_LAYOUT;
    return support;
  }
  if ((info.bindFlags & BIND_VERTEX_BUFFER) && (vk.buffer & VK_FORMAT_FEATURE_2_VERTEX_BUFFER_BIT))
    support |= FORMAT_SUPPORT_IA_VERTEX_BUFFER;
  if (info.bindFlags & BIND_INDEX_BUFFER) support |= FORMAT_SUPPORT_IA_INDEX_BUFFER;
  if ((info.bindFlags & BIND_SHADER_RESOURCE) && (vk.buffer & VK_FORMAT_FEATURE_2_UNIFORM_TEXEL_BUFFER_BIT))
    support |= FORMAT_SUPPORT_BUFFER;
  if ((info.bindFlags & BIND_SHADER_RESOURCE) && (vk.image & VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_BIT)) {
    support |= kTextureDimensions | FORMAT_SUPPORT_SHADER_LOAD;
    // D3D11 samples and gathers only non-integer formats.
    if (!integer && (vk.image & VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_FILTER_LINEAR_BIT))
      support |= FORMAT_SUPPORT_SHADER_SAMPLE | FORMAT_SUPPORT_SHADER_GATHER;
  }
  if ((info.bindFlags & BIND_RENDER_TARGET) && (vk.image & VK_FORMAT_FEATURE_2_COLOR_ATTACHMENT_BIT)) {
    support |= FORMAT_SUPPORT_RENDER_TARGET | kTextureDimensions;
    if (vk.image & VK_FORMAT_FEATURE_2_COLOR_ATTACHMENT_BLEND_BIT) support |= FORMAT_SUPPORT_BLENDABLE;
    constexpr VkFormatFeatureFlags2 kBlit = VK_FORMAT_FEATURE_2_BLIT_SRC_BIT | VK_FORMAT_FEATURE_2_BLIT_DST_BIT |
                                            VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
    if (!integer && (vk.image & kBlit) == kBlit && (info.bindFlags & BIND_SHADER_RESOURCE))
      support |= FORMAT_SUPPORT_MIP_AUTOGEN;
  }
  if ((info.bindFlags & BIND_DEPTH_STENCIL) && info.isDepth) {
    const VkFormat depth = states::PickDepthFormat(info.format, [&](VkFormat f) {
      return (FeaturesOf(gpu, f).image & VK_FORMAT_FEATURE_2_DEPTH_STENCIL_ATTACHMENT_BIT) != 0;
    });
    if (depth != VK_FORMAT_UNDEFINED)
      support |= FORMAT_SUPPORT_DEPTH_STENCIL | (kTextureDimensions & ~FORMAT_SUPPORT_TEXTURE3D);
  }
  // Multisampled targets: what CheckMultisampleQualityLevels answers from.
  if (TargetSampleCounts(gpu, info.format) & ~VkSampleCountFlags(VK_SAMPLE_COUNT_1_BIT)) {
    support |= FORMAT_SUPPORT_MULTISAMPLE_RENDERTARGET | FORMAT_SUPPORT_MULTISAMPLE_LOAD;
    if ((support & FORMAT_SUPPORT_RENDER_TARGET) && !integer) support |= FORMAT_SUPPORT_MULTISAMPLE_RESOLVE;
  }
  if ((info.bindFlags & BIND_UNORDERED_ACCESS) && (vk.image & VK_FORMAT_FEATURE_2_STORAGE_IMAGE_BIT))
    support |= FORMAT_SUPPORT_TYPED_UNORDERED_ACCESS_VIEW;
  return support;
}

UINT FormatSupport2(const Gpu& gpu, const states::FormatInfo& info) {
  if (!(info.bindFlags & BIND_UNORDERED_ACCESS)) return 0;
  const FormatFeatures vk = FeaturesOf(gpu, info.vkFormat);
  UINT support = 0;
  if (vk.image & VK_FORMAT_FEATURE_2_STORAGE_IMAGE_BIT) support |= FORMAT_SUPPORT2_UAV_TYPED_STORE;
  // Feature level 11_0 loads typed UAVs only as R32_UINT, R32_SINT and R32_FLOAT.
  const bool r32 = info.format == DXGI_FORMAT_R32_UINT || info.format == DXGI_FORMAT_R32_SINT ||
                   info.format == DXGI_FORMAT_R32_FLOAT;
  if (r32 && (vk.image & VK_FORMAT_FEATURE_2_STORAGE_IMAGE_BIT)) support |= FORMAT_SUPPORT2_UAV_TYPED_LOAD;
  const bool integer32 = info.format == DXGI_FORMAT_R32_UINT || info.format == DXGI_FORMAT_R32_SINT;
  if (integer32 && (vk.image & VK_FORMAT_FEATURE_2_STORAGE_IMAGE_ATOMIC_BIT))
    support |= FORMAT_SUPPORT2_UAV_ATOMIC_ADD | FORMAT_SUPPORT2_UAV_ATOMIC_BITWISE_OPS |
               FORMAT_SUPPORT2_UAV_ATOMIC_COMPARE_STORE_OR_COMPARE_EXCHANGE | FORMAT_SUPPORT2_UAV_ATOMIC_EXCHANGE |
               FORMAT_SUPPORT2_UAV_ATOMIC_SIGNED_MIN_OR_MAX | FORMAT_SUPPORT2_UAV_ATOMIC_UNSIGNED_MIN_OR_MAX;
  return support;
}

// Copies `data` into CheckFeatureSupport's output after checking its size.
template <class T>
HRESULT Answer(const Gpu& gpu, void* out, UINT size, const T& data, const char* feature) {
  if (!out || size != sizeof(T))
    return gpu.Refuse(std::string("CheckFeatureSupport: ") + feature + " needs pFeatureSupportData of " +
                      std::to_string(sizeof(T)) + " bytes, got " + std::to_string(size));
  *static_cast<T*>(out) = data;
  return S_OK;
}

}  // namespace

UINT DeviceImpl::GetCreationFlags() { return gpu_->Validating() ? CREATE_DEVICE_DEBUG : 0; }

HRESULT DeviceImpl::GetDeviceRemovedReason() { return gpu_->DeviceLost() ? DXGI_ERROR_DEVICE_REMOVED : S_OK; }

HRESULT DeviceImpl::SetExceptionMode(UINT RaiseFlags) {
  if (RaiseFlags & ~UINT(RAISE_FLAG_DRIVER_INTERNAL_ERROR))
    return gpu_->Refuse("SetExceptionMode: RaiseFlags " + std::to_string(RaiseFlags) +
                        " has bits other than RAISE_FLAG_DRIVER_INTERNAL_ERROR");
  exceptionMode_ = RaiseFlags;
  return S_OK;
}

HRESULT DeviceImpl::CheckFormatSupport(DXGI_FORMAT Format, UINT* pFormatSupport) {
  if (!pFormatSupport) return gpu_->Refuse("CheckFormatSupport: pFormatSupport is NULL");
  const states::FormatInfo* info = states::GetFormatInfo(Format);
  *pFormatSupport = info ? FormatSupport(*gpu_, *info) : 0;
  return *pFormatSupport ? S_OK : E_FAIL;
}

HRESULT DeviceImpl::CheckFeatureSupport(FEATURE Feature, void* pFeatureSupportData, UINT FeatureSupportDataSize) {
  const Gpu& gpu = *gpu_;
  switch (Feature) {
    case FEATURE_THREADING:
      // Command lists are recorded by the runtime, not the driver (D3D11's
      // emulation): FALSE, as D3D11 reports for drivers without them.
      return Answer(gpu, pFeatureSupportData, FeatureSupportDataSize, FEATURE_DATA_THREADING{FALSE, FALSE},
                    "FEATURE_THREADING");
    case FEATURE_DOUBLES: {
      VkPhysicalDeviceFeatures features;
      vkGetPhysicalDeviceFeatures(gpu.Physical(), &features);
      return Answer(gpu, pFeatureSupportData, FeatureSupportDataSize,
                    FEATURE_DATA_DOUBLES{features.shaderFloat64 ? TRUE : FALSE}, "FEATURE_DOUBLES");
    }
    case FEATURE_FORMAT_SUPPORT:
    case FEATURE_FORMAT_SUPPORT2: {
      const bool second = Feature == FEATURE_FORMAT_SUPPORT2;
      const char* name = second ? "FEATURE_FORMAT_SUPPORT2" : "FEATURE_FORMAT_SUPPORT";
      static_assert(sizeof(FEATURE_DATA_FORMAT_SUPPORT) == sizeof(FEATURE_DATA_FORMAT_SUPPORT2));
      if (!pFeatureSupportData || FeatureSupportDataSize != sizeof(FEATURE_DATA_FORMAT_SUPPORT))
        return Answer(gpu, nullptr, FeatureSupportDataSize, FEATURE_DATA_FORMAT_SUPPORT{}, name);
      auto* data = static_cast<FEATURE_DATA_FORMAT_SUPPORT*>(pFeatureSupportData);
      const states::FormatInfo* info = states::GetFormatInfo(data->InFormat);
      data->OutFormatSupport = !info ? 0 : second ? FormatSupport2(gpu, *info) : FormatSupport(gpu, *info);
      return info ? S_OK : E_FAIL;
    }
    case FEATURE_D3D10_X_HARDWARE_OPTIONS:
      return Answer(gpu, pFeatureSupportData, FeatureSupportDataSize, FEATURE_DATA_D3D10_X_HARDWARE_OPTIONS{TRUE},
                    "FEATURE_D3D10_X_HARDWARE_OPTIONS");
  }
  return gpu.Refuse("CheckFeatureSupport: Feature " + std::to_string(Feature) +
                    " is not a Direct3D 11.0 feature (FEATURE_THREADING .. FEATURE_D3D10_X_HARDWARE_OPTIONS)");
}

HRESULT DeviceImpl::CreateClassLinkage(ClassLinkage** ppLinkage) {
  if (ppLinkage) *ppLinkage = nullptr;
  gpu_->Report(MESSAGE_CATEGORY_STATE_CREATION, MESSAGE_SEVERITY_ERROR,
               "CreateClassLinkage: dynamic shader linkage (HLSL interfaces and class instances) has no SPIR-V "
               "counterpart; compile one shader per class combination instead");
  return E_NOTIMPL;
}

void DeviceImpl::CheckCounterInfo(COUNTER_INFO* pCounterInfo) {
  if (pCounterInfo) *pCounterInfo = {COUNTER(0), 0, 0};
}

HRESULT DeviceImpl::CreateCounter(const COUNTER_DESC* pCounterDesc, Counter** ppCounter) {
  if (ppCounter) *ppCounter = nullptr;
  gpu_->Report(MESSAGE_CATEGORY_STATE_CREATION, MESSAGE_SEVERITY_ERROR,
               "CreateCounter: counter " + std::to_string(pCounterDesc ? pCounterDesc->Counter : 0) +
                   " is not supported: the device has no device-dependent counters (CheckCounterInfo); use "
                   "QUERY_PIPELINE_STATISTICS and QUERY_TIMESTAMP queries");
  return DXGI_ERROR_UNSUPPORTED;
}

HRESULT DeviceImpl::CheckCounter(const COUNTER_DESC* pDesc, COUNTER_TYPE*, UINT*, LPSTR, UINT*, LPSTR, UINT*, LPSTR,
                                 UINT*) {
  return gpu_->Refuse("CheckCounter: counter " + std::to_string(pDesc ? pDesc->Counter : 0) +
                      " does not exist: the device has no device-dependent counters (CheckCounterInfo)");
}

HRESULT DeviceImpl::OpenSharedResource(HANDLE, REFIID, void** ppResource) {
  if (ppResource) *ppResource = nullptr;
  return gpu_->Refuse("OpenSharedResource: the handle names no shared resource: this backend shares no resources "
                      "across devices or processes (RESOURCE_MISC_SHARED is not supported)");
}

}  // namespace rhi::vk
