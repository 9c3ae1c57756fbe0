// Load time of a large effect (20 techniques), cold (empty cache: every shader
// compiled by glslang) and warm (every shader from the SPIR-V cache).
// Usage: fx_load_time [runs]   -- prints the medians in milliseconds.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "fx/effect.h"

namespace {

// 20 techniques, each with its own VS/PS pair (a uniform argument makes each distinct).
std::string LargeEffect() {
  std::string fx = R"(
cbuffer PerFrame { float4x4 ViewProj; float4 Tint = float4(1, 0.5, 0.25, 1); float Time; };
Texture2D Albedo;
SamplerState Linear { Filter = MIN_MAG_MIP_LINEAR; };
struct VsOut { float4 pos : SV_Position; float2 uv : TEXCOORD0; };
VsOut VS(float3 p : POSITION, float2 uv : TEXCOORD0, uniform float scale) {
  VsOut o; o.pos = mul(ViewProj, float4(p * scale, 1)); o.uv = uv; return o;
}
float4 PS(VsOut i, uniform int variant) : SV_Target {
  float4 c = Albedo.Sample(Linear, i.uv) * Tint;
  for (int k = 0; k < variant; ++k) c.rgb = c.gbr * 0.9 + sin(Time + k) * 0.1;
  return c;
}
BlendState Additive { BlendEnable[0] = TRUE; SrcBlend[0] = ONE; DestBlend[0] = ONE; };
)";
  for (int t = 0; t < 20; ++t) {
    fx += "technique11 T" + std::to_string(t) + " { pass P0 { SetVertexShader(CompileShader(vs_5_0, VS(" +
          std::to_string(t + 1) + ".0))); SetPixelShader(CompileShader(ps_5_0, PS(" + std::to_string(t) +
          "))); SetBlendState(Additive, float4(0,0,0,0), 0xFFFFFFFF); } }\n";
  }
  return fx;
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  rhi::ComPtr<rhi::Device> device;
  rhi::ComPtr<rhi::DeviceContext> context;
  if (rhi::FAILED(rhi::CreateDevice(nullptr, device.GetAddressOf(), context.GetAddressOf()))) return 1;
  const std::string source = LargeEffect();
  const std::string cacheDir = std::filesystem::temp_directory_path() / "fx_load_time_cache";
  std::vector<double> cold, warm;
  fx::EFFECT_DESC coldDesc{}, warmDesc{};
  for (int r = 0; r < runs; ++r) {
    for (bool isWarm : {false, true}) {
      if (!isWarm) std::filesystem::remove_all(cacheDir);
      std::string errors;
      fx::EFFECT_OPTIONS options;
      options.CacheDirectory = cacheDir;
      options.Errors = &errors;
      rhi::ComPtr<fx::Effect> effect;
      auto start = std::chrono::steady_clock::now();
      rhi::HRESULT hr = fx::CreateEffectFromMemory(source.data(), source.size(), "large.fx", options, device.Get(),
                                                   effect.GetAddressOf());
      double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      if (rhi::FAILED(hr)) {
        std::fprintf(stderr, "%s", errors.c_str());
        return 1;
      }
      effect->GetDesc(isWarm ? &warmDesc : &coldDesc);
      (isWarm ? warm : cold).push_back(ms);
    }
  }
  std::filesystem::remove_all(cacheDir);
  std::printf("device: %s\n", device->GetAdapterName());
  std::printf("effect: %u techniques, %zu source bytes; %d runs each\n", warmDesc.Techniques, source.size(), runs);
  std::printf("cold (compiled %u, cached %u): median %.2f ms\n", coldDesc.ShadersCompiled, coldDesc.ShadersFromCache,
              Median(cold));
  std::printf("warm (compiled %u, cached %u): median %.2f ms\n", warmDesc.ShadersCompiled, warmDesc.ShadersFromCache,
              Median(warm));
  return 0;
}
