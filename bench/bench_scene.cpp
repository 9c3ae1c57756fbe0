#include "bench_scene.h"

#include <cstdio>
#include <cstdlib>

#include "hlsl/hlsl_compiler.h"

namespace bench {

namespace {

constexpr const char* kSceneHlsl = R"hlsl(
cbuffer DrawConstants : register(b0) {
  float4 offset;  // xy: translation, zw: scale
  float4 color;
};

struct VSOut {
  float4 position : SV_Position;
  float4 color : COLOR0;
};

VSOut VSMain0(float2 position : POSITION) {
  VSOut o;
  o.position = float4(position + offset.xy, 0.5, 1.0);
  o.color = color;
  return o;
}

VSOut VSMain1(float2 position : POSITION) {
  VSOut o;
  o.position = float4(position * offset.zw + offset.xy, 0.25, 1.0);
  o.color = color.bgra;
  return o;
}

float4 PSMain0(VSOut i) : SV_Target { return i.color; }

float4 PSMain1(VSOut i) : SV_Target { return i.color * 0.5 + 0.25; }
)hlsl";

std::vector<uint32_t> Compile(const char* entry, const char* profile) {
  hlsl::CompileRequest request;
  request.source = kSceneHlsl;
  request.fileName = "rhi_bench_scene.hlsl";
  request.entryPoint = entry;
  request.profile = profile;
  hlsl::CompileResult result = hlsl::CompileHlsl(request);
  if (!result.ok) {
    std::fprintf(stderr, "rhi_bench: compiling %s (%s) failed:\n%s\n", entry, profile, result.FormatErrors().c_str());
    std::exit(2);
  }
  return std::move(result.spirv);
}

}  // namespace

SceneShaders CompileSceneShaders() {
  SceneShaders shaders;
  shaders.vs[0] = Compile("VSMain0", "vs_5_0");
  shaders.vs[1] = Compile("VSMain1", "vs_5_0");
  shaders.ps[0] = Compile("PSMain0", "ps_5_0");
  shaders.ps[1] = Compile("PSMain1", "ps_5_0");
  return shaders;
}

}  // namespace bench
