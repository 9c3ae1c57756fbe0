// What the peeling methods (depth_peeling.cpp, dual_depth_peeling.cpp) render
// into and read back: colour targets (one or several slices), depth buffers that
// are also textures, and the full-screen passes over the frame.
#pragma once

#include <string>
#include <vector>

#include "fx/effect.h"
#include "renderer/oit/method.h"

namespace renderer::oit {

// A colour target of the frame's size: one texture (Create), or an array of
// `sliceCount` (CreateArray, viewed as a Texture2DArray even with one slice), with a
// render-target view of each slice and one shader-resource view of it all.
struct ColourTarget {
  rhi::ComPtr<rhi::Texture2D> texture;
  std::vector<rhi::ComPtr<rhi::RenderTargetView>> slices;
  rhi::ComPtr<rhi::ShaderResourceView> srv;
  uint64_t bytes = 0;

  bool Create(rhi::Device* device, const FrameDesc& frame, rhi::DXGI_FORMAT format);
  bool CreateArray(rhi::Device* device, const FrameDesc& frame, rhi::DXGI_FORMAT format, uint32_t sliceCount);
  rhi::RenderTargetView* rtv(uint32_t slice = 0) const { return slices[slice].Get(); }
};

// A depth buffer that later passes read: R32_TYPELESS, tested and written through a
// D32_FLOAT depth-stencil view, read through an R32_FLOAT shader-resource view.
struct DepthTexture {
  rhi::ComPtr<rhi::Texture2D> texture;
  rhi::ComPtr<rhi::DepthStencilView> dsv;
  rhi::ComPtr<rhi::ShaderResourceView> srv;
  uint64_t bytes = 0;

  bool Create(rhi::Device* device, const FrameDesc& frame);
};

// Unbinds every pixel-shader resource, D3D11's way to hand textures a pass read back
// to the output merger without the runtime's hazard warnings.
void UnbindPixelShaderResources(rhi::DeviceContext* context);

// A full-screen triangle over the frame alone (no depth buffer) with `pass`.
void DrawOverFrame(rhi::DeviceContext* context, rhi::RenderTargetView* frame, fx::EffectPass* pass);

// The float32 composite the peeling methods blend their layers over
// (shaders_hlsl/oit/float_composite.hlsli): Load copies the opaque frame in, Store
// copies it back into the frame, rounded once, with the effect's LoadFrame and
// StoreFrame passes.
class FloatComposite {
 public:
  bool Create(rhi::Device* device, const FrameDesc& frame, fx::Effect* effect, std::string* error);
  void Load(rhi::DeviceContext* context, rhi::ShaderResourceView* frame) const;
  void Store(rhi::DeviceContext* context, rhi::RenderTargetView* frame) const;
  rhi::RenderTargetView* rtv() const { return target_.rtv(); }
  uint64_t bytes() const { return target_.bytes; }

 private:
  void Copy(rhi::DeviceContext* context, rhi::ShaderResourceView* source, rhi::RenderTargetView* target,
            fx::EffectPass* pass) const;
  ColourTarget target_;  // R32G32B32A32_FLOAT
  fx::EffectPass *load_ = nullptr, *store_ = nullptr;
  fx::EffectShaderResourceVariable* source_ = nullptr;
};

}  // namespace renderer::oit
