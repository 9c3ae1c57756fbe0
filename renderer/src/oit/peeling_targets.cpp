#include "oit/peeling_targets.h"

#include "renderer/effect_files.h"
#include "rhi/format_info.h"

namespace renderer::oit {

using namespace rhi;

namespace {

TEXTURE2D_DESC ColourDesc(const FrameDesc& frame, DXGI_FORMAT format, uint32_t slices) {
  return {frame.width, frame.height, 1, slices, format, {1, 0}, USAGE_DEFAULT,
          BIND_RENDER_TARGET | BIND_SHADER_RESOURCE, 0, 0};
}

}  // namespace

bool ColourTarget::Create(Device* device, const FrameDesc& frame, DXGI_FORMAT format) {
  const TEXTURE2D_DESC d = ColourDesc(frame, format, 1);
  bytes = TextureBytes(d);
  slices.resize(1);
  return SUCCEEDED(device->CreateTexture2D(&d, nullptr, texture.GetAddressOf())) &&
         SUCCEEDED(device->CreateShaderResourceView(texture.Get(), nullptr, srv.GetAddressOf())) &&
         SUCCEEDED(device->CreateRenderTargetView(texture.Get(), nullptr, slices[0].GetAddressOf()));
}

bool ColourTarget::CreateArray(Device* device, const FrameDesc& frame, DXGI_FORMAT format, uint32_t sliceCount) {
  const TEXTURE2D_DESC d = ColourDesc(frame, format, sliceCount);
  bytes = TextureBytes(d);
  SHADER_RESOURCE_VIEW_DESC all{};
  all.Format = format;
  all.ViewDimension = SRV_DIMENSION_TEXTURE2DARRAY;
  all.Texture2DArray = {0, 1, 0, sliceCount};
  if (FAILED(device->CreateTexture2D(&d, nullptr, texture.GetAddressOf())) ||
      FAILED(device->CreateShaderResourceView(texture.Get(), &all, srv.GetAddressOf())))
    return false;
  slices.resize(sliceCount);
  for (uint32_t i = 0; i < sliceCount; ++i) {
    RENDER_TARGET_VIEW_DESC one{format, RTV_DIMENSION_TEXTURE2DARRAY, {}};
    one.Texture2DArray = {0, i, 1};
    if (FAILED(device->CreateRenderTargetView(texture.Get(), &one, slices[i].GetAddressOf()))) return false;
  }
  return true;
}

bool DepthTexture::Create(Device* device, const FrameDesc& frame) {
  const TEXTURE2D_DESC d{frame.width,   frame.height, 1, 1, DXGI_FORMAT_R32_TYPELESS, {1, 0},
                         USAGE_DEFAULT, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE, 0, 0};
  bytes = TextureBytes(d);
  DEPTH_STENCIL_VIEW_DESC depth{DXGI_FORMAT_D32_FLOAT, DSV_DIMENSION_TEXTURE2D, 0, {}};
  SHADER_RESOURCE_VIEW_DESC read{};
  read.Format = DXGI_FORMAT_R32_FLOAT;
  read.ViewDimension = SRV_DIMENSION_TEXTURE2D;
  read.Texture2D = {0, 1};
  return SUCCEEDED(device->CreateTexture2D(&d, nullptr, texture.GetAddressOf())) &&
         SUCCEEDED(device->CreateDepthStencilView(texture.Get(), &depth, dsv.GetAddressOf())) &&
         SUCCEEDED(device->CreateShaderResourceView(texture.Get(), &read, srv.GetAddressOf()));
}

void UnbindPixelShaderResources(DeviceContext* context) {
  ShaderResourceView* none[COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT] = {};
  context->PSSetShaderResources(0, COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT, none);
}

void DrawOverFrame(DeviceContext* context, RenderTargetView* frame, fx::EffectPass* pass) {
  context->OMSetRenderTargets(1, &frame, nullptr);
  context->IASetInputLayout(nullptr);
  context->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  pass->Apply(0, context);
  context->Draw(3, 0);
}

bool FloatComposite::Create(Device* device, const FrameDesc& frame, fx::Effect* effect, std::string* error) {
  if (!target_.Create(device, frame, DXGI_FORMAT_R32G32B32A32_FLOAT))
    return *error = "creating the float32 composite failed", false;
  source_ = effect->GetVariableByName("CopySource")->AsShaderResource();
  return (load_ = FindPass(effect, nullptr, "LoadFrame", error)) &&
         (store_ = FindPass(effect, nullptr, "StoreFrame", error));
}

void FloatComposite::Load(DeviceContext* context, ShaderResourceView* frame) const {
  Copy(context, frame, target_.rtv(), load_);
}

void FloatComposite::Store(DeviceContext* context, RenderTargetView* frame) const {
  Copy(context, target_.srv.Get(), frame, store_);
}

// The target may be what the pass before read, and the source what the next one
// renders to: both leave the pixel shader's resources unbound.
void FloatComposite::Copy(DeviceContext* context, ShaderResourceView* source, RenderTargetView* target,
                          fx::EffectPass* pass) const {
  UnbindPixelShaderResources(context);
  source_->SetResource(source);
  DrawOverFrame(context, target, pass);
  UnbindPixelShaderResources(context);
}

}  // namespace renderer::oit
