// Blend, depth-stencil, rasterizer and sampler state objects: immutable,
// validated and deduplicated at creation (rhi/src/states holds the rules).
#pragma once

#include "device.h"
#include "object_caches.h"

namespace rhi::vk {

template <class Interface, class Desc>
class StateObject : public DeviceChildImpl<Interface> {
 public:
  // `desc` is normalised; `contentId` stands for it in pipeline keys.
  StateObject(DeviceImpl* device, const Desc& desc, uint64_t contentId)
      : DeviceChildImpl<Interface>(device), desc_(desc), contentId_(contentId) {}
  ~StateObject() override { this->device().caches().Of(&desc_).Forget(desc_, this); }
  void GetDesc(Desc* desc) override { *desc = desc_; }
  const Desc& desc() const { return desc_; }
  uint64_t contentId() const { return contentId_; }

 private:
  Desc desc_;
  uint64_t contentId_;
};

using BlendStateImpl = StateObject<BlendState, BLEND_DESC>;
using DepthStencilStateImpl = StateObject<DepthStencilState, DEPTH_STENCIL_DESC>;
using RasterizerStateImpl = StateObject<RasterizerState, RASTERIZER_DESC>;

class SamplerStateImpl final : public StateObject<SamplerState, SAMPLER_DESC> {
 public:
  SamplerStateImpl(DeviceImpl* device, const SAMPLER_DESC& desc, uint64_t contentId);
  ~SamplerStateImpl() override;
  VkSampler handle() const { return sampler_; }
  HRESULT Initialize();

 private:
  VkSampler sampler_ = VK_NULL_HANDLE;
};

// The descs in effect for a binding, NULL meaning the D3D11 default.
const BLEND_DESC& BlendDescOf(DeviceChild* state);
const DEPTH_STENCIL_DESC& DepthStencilDescOf(DeviceChild* state);
const RASTERIZER_DESC& RasterizerDescOf(DeviceChild* state);

}  // namespace rhi::vk
