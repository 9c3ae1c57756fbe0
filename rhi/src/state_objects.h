// Blend, depth-stencil, rasterizer and sampler state objects: immutable,
// validated and deduplicated at creation (rhi/src/states holds the rules).
#pragma once

#include "device.h"

namespace rhi::vk {

template <class Interface, class Desc>
class StateObject : public DeviceChildImpl<Interface> {
 public:
  StateObject(DeviceImpl* device, const Desc& desc) : DeviceChildImpl<Interface>(device), desc_(desc) {}
  ~StateObject() override { this->device().ForgetState(this); }
  void GetDesc(Desc* desc) override { *desc = desc_; }
  const Desc& desc() const { return desc_; }

 private:
  Desc desc_;
};

using BlendStateImpl = StateObject<BlendState, BLEND_DESC>;
using DepthStencilStateImpl = StateObject<DepthStencilState, DEPTH_STENCIL_DESC>;
using RasterizerStateImpl = StateObject<RasterizerState, RASTERIZER_DESC>;

class SamplerStateImpl final : public StateObject<SamplerState, SAMPLER_DESC> {
 public:
  SamplerStateImpl(DeviceImpl* device, const SAMPLER_DESC& desc);
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
