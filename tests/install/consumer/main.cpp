// Built against the installed package by tests/install (run_install_test.cmake), as a ported
// D3D11 program would be: a device, an effect from memory (D3DX11CreateEffectFromMemory's
// shape), a BC1 DDS texture from memory (DirectXTK's CreateDDSTextureFromMemory), a full-screen
// draw into a 4x4 target and the pixels read back. Prints "consumer: ok" and exits 0 on success.
#include <cstdio>
#include <string>
#include <vector>

#include "fx/effect.h"
#include "rhi/capture.h"
#include "rhi/rhi.h"
#include "rhi/texture_files.h"

namespace {

const char kEffect[] = R"(
Texture2D Tex;
float4 Tint = float4(1.0, 0.5, 1.0, 1.0);
float4 VS(uint id : SV_VertexID) : SV_Position {
  float2 uv = float2((id << 1) & 2, id & 2);
  return float4(uv * float2(2, -2) + float2(-1, 1), 0.5, 1);
}
float4 PS(float4 pos : SV_Position) : SV_Target { return Tex.Load(int3(pos.xy, 0)) * Tint; }
technique11 Fill { pass P0 {
  SetVertexShader(CompileShader(vs_5_0, VS()));
  SetPixelShader(CompileShader(ps_5_0, PS()));
} }
)";

// A DDS file: the legacy header, FourCC DXT1, 4x4, one BC1 block of colour0 white (0xFFFF)
// and colour1 black with every index 0: every texel white.
std::vector<uint8_t> WhiteBc1Dds() {
  std::vector<uint8_t> file;
  auto put = [&](uint32_t v) {
    for (int i = 0; i < 4; ++i) file.push_back(uint8_t(v >> (8 * i)));
  };
  put(0x20534444);  // "DDS "
  for (uint32_t v : {124u, 0x1007u, 4u, 4u, 0u, 0u, 1u}) put(v);
  for (int i = 0; i < 11; ++i) put(0);
  for (uint32_t v : {32u, 0x4u, 0x31545844u /* DXT1 */, 0u, 0u, 0u, 0u, 0u}) put(v);
  for (uint32_t v : {0x1000u, 0u, 0u, 0u, 0u}) put(v);
  for (uint32_t v : {0x0000FFFFu, 0u}) put(v);  // colour0 white, colour1 black; indices 0
  return file;
}

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
  rhi::ComPtr<fx::Effect> effect;
  if (rhi::HRESULT hr = fx::CreateEffectFromMemory(kEffect, sizeof kEffect - 1, "consumer.fx", {}, 0, device.Get(),
                                                   effect.GetAddressOf(), &errors);
      rhi::FAILED(hr)) {
    std::fprintf(stderr, "%s", errors.c_str());
    return Fail("CreateEffectFromMemory", hr);
  }
  const std::vector<uint8_t> dds = WhiteBc1Dds();
  rhi::ComPtr<rhi::ShaderResourceView> textureView;
  if (rhi::HRESULT hr = rhi::CreateDDSTextureFromMemory(device.Get(), dds.data(), dds.size(), nullptr,
                                                        textureView.GetAddressOf(), 0, nullptr, &errors);
      rhi::FAILED(hr)) {
    std::fprintf(stderr, "%s\n", errors.c_str());
    return Fail("CreateDDSTextureFromMemory", hr);
  }
  effect->GetVariableByName("Tex")->AsShaderResource()->SetResource(textureView.Get());

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
  if (r != 255 || g != 128 || b != 255 || a != 255 || messages) return 1;  // white texel * Tint
  std::printf("consumer: ok\n");
  return 0;
}
