#include "state_objects.h"

#include "states/sampler.h"
#include "vk_check.h"

namespace rhi::vk {

// Default-constructed descs carry the D3D11 defaults (see d3d11_types.h).
const BLEND_DESC& BlendDescOf(DeviceChild* state) {
  static const BLEND_DESC kDefault{};
  return state ? static_cast<BlendStateImpl*>(state)->desc() : kDefault;
}

const DEPTH_STENCIL_DESC& DepthStencilDescOf(DeviceChild* state) {
  static const DEPTH_STENCIL_DESC kDefault{};
  return state ? static_cast<DepthStencilStateImpl*>(state)->desc() : kDefault;
}

const RASTERIZER_DESC& RasterizerDescOf(DeviceChild* state) {
  static const RASTERIZER_DESC kDefault{};
  return state ? static_cast<RasterizerStateImpl*>(state)->desc() : kDefault;
}

SamplerStateImpl::SamplerStateImpl(DeviceImpl* device, const SAMPLER_DESC& desc, uint64_t contentId)
    : StateObject(device, desc, contentId) {}

HRESULT SamplerStateImpl::Initialize() {
  states::SamplerLimits limits{gpu().Caps().limits.maxSamplerAnisotropy, gpu().Caps().limits.maxSamplerLodBias};
  states::SamplerVk sampler = states::ToVulkan(desc(), limits);
  if (sampler.needsCustomBorderColor && !gpu().Caps().customBorderColor)
    return gpu().Refuse("CreateSamplerState: BorderColor needs VK_EXT_custom_border_color, which " +
                        gpu().AdapterName() + " lacks");
  if (sampler.needsCustomBorderColor) sampler.info.pNext = &sampler.customBorder;
  return ToHresult(vkCreateSampler(gpu().Device(), &sampler.info, nullptr, &sampler_));
}

SamplerStateImpl::~SamplerStateImpl() {
  VkDevice vkDevice = gpu().Device();
  VkSampler sampler = sampler_;
  gpu().DeferDestroy([=] { vkDestroySampler(vkDevice, sampler, nullptr); });
}

}  // namespace rhi::vk
