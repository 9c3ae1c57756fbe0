// Built against the installed package by tests/install (run_install_test.cmake): creates a
// device, an effect from memory, draws a full-screen triangle into a 4x4 target and checks
// the pixel it reads back. Prints "consumer: ok" and exits 0 on success.
#include <cstdio>
#include <string>
#include <vector>

#include "fx/effect.h"
#include "rhi/capture.h"
#include "rhi/rhi.h"

namespace {

const char kEffect[] = R"(
float4 Color = float4(1.0, 0.5, 0.0, 1.0);
float4 VS(uint id : SV_VertexID) : SV_Position {
  float2 uv = float2((id << 1) & 2, id & 2);
  return float4(uv * float2(2, -2) + float2(-1, 1), 0.5, 1);
}
float4 PS(float4 pos : SV_Position) : SV_Target { return Color; }
technique11 Fill { pass P0 {
  SetVertexShader(CompileShader(vs_5_0, VS()));
  SetPixelShader(CompileShader(ps_5_0, PS()));
} }
)";

int Fail(const char* what, rhi::HRESULT hr) {
  std::fprintf(stderr, "consumer: %s failed (0x%08x)\n", what, static_cast<unsigned>(hr));
  return 1;
}

}  // namespace

int main() {
  int messages = 0;
  rhi::DEVICE_OPTIONS options;
  options.EnableValidation = rhi::TRUE;
  options.OnMessage = [&](rhi::MESSAGE_CATEGORY, rhi::MESSAGE_SEVERITY, const char* description) {
    std::fprintf(stderr, "consumer: device message: %s\n", description);
    ++messages;
  };
  rhi::ComPtr<rhi::Device> device;
  rhi::ComPtr<rhi::DeviceContext> context;
  if (rhi::HRESULT hr = rhi::CreateDevice(&options, device.GetAddressOf(), context.GetAddressOf()); rhi::FAILED(hr))
    return Fail("CreateDevice", hr);

  std::string errors;
  fx::EFFECT_OPTIONS effectOptions;
  effectOptions.CacheDirectory = "";
  effectOptions.Errors = &errors;
  rhi::ComPtr<fx::Effect> effect;
  if (rhi::HRESULT hr = fx::CreateEffectFromMemory(kEffect, sizeof kEffect - 1, "consumer.fx", effectOptions,
                                                   device.Get(), effect.GetAddressOf());
      rhi::FAILED(hr)) {
    std::fprintf(stderr, "%s", errors.c_str());
    return Fail("CreateEffectFromMemory", hr);
  }

  rhi::TEXTURE2D_DESC desc = {};
  desc.Width = desc.Height = 4;
  desc.MipLevels = desc.ArraySize = 1;
  desc.Format = rhi::DXGI_FORMAT_R8G8B8A8_UNORM;
  desc.SampleDesc.Count = 1;
  desc.BindFlags = rhi::BIND_RENDER_TARGET;
  rhi::ComPtr<rhi::Texture2D> target;
  rhi::ComPtr<rhi::RenderTargetView> rtv;
  if (rhi::HRESULT hr = device->CreateTexture2D(&desc, nullptr, target.GetAddressOf()); rhi::FAILED(hr))
    return Fail("CreateTexture2D", hr);
  if (rhi::HRESULT hr = device->CreateRenderTargetView(target.Get(), nullptr, rtv.GetAddressOf()); rhi::FAILED(hr))
    return Fail("CreateRenderTargetView", hr);

  rhi::VIEWPORT viewport = {0, 0, 4, 4, 0, 1};
  context->RSSetViewports(1, &viewport);
  context->OMSetRenderTargets(1, rtv.GetAddressOf(), nullptr);
  context->IASetPrimitiveTopology(rhi::PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  effect->GetTechniqueByName("Fill")->GetPassByIndex(0)->Apply(0, context.Get());
  context->Draw(3, 0);

  std::vector<uint8_t> texels;
  if (rhi::HRESULT hr = rhi::CaptureTexture2D(device.Get(), context.Get(), target.Get(), 0, &texels); rhi::FAILED(hr))
    return Fail("CaptureTexture2D", hr);
  const unsigned r = texels[0], g = texels[1], b = texels[2], a = texels[3];
  std::printf("consumer: pixel (0,0) = %u %u %u %u on %s\n", r, g, b, a, device->GetAdapterName());
  if (r != 255 || g != 128 || b != 0 || a != 255 || messages) return 1;
  std::printf("consumer: ok\n");
  return 0;
}
