#include "oit_fixture.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include <fstream>
#include <sstream>

#include "fx/effect.h"
#include "renderer/effect_files.h"
#include "rhi_reference/blend.h"
#include "rhi_reference/composite.h"
#include "rhi_reference/tolerance.h"

namespace conf {

using namespace rhi;
namespace ref = rhi::reference;

const char* OitMethodName(OitMethod method) {
  switch (method) {
    case OitMethod::Wboit: return "WBOIT (Tables 1+2)";
    case OitMethod::ColoredLiteral: return "Colored OIT, Table 4 as printed (INV_SRC_ALPHA/ONE)";
    case OitMethod::ColoredCorrected: return "Colored OIT, Table 4 corrected (SRC_ALPHA/ONE)";
  }
  return "?";
}

OitScene MakeOitScene(uint32_t seed) {
  OitScene s;
  std::mt19937 rng(seed);
  auto u = [&](float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng); };
  for (int p = 0; p < kOitPixels; ++p) {
    s.background[p] = {u(0, 1), u(0, 1), u(0, 1), 1.0f};
    for (int l = 0; l < kOitLayers; ++l)
      s.layers[p][l] = {{u(0, 1), u(0, 1), u(0, 1), u(0.1f, 0.9f)}, {u(0, 1), u(0, 1), u(0, 1)}, u(0.05f, 0.95f)};
  }
  s.background[0] = {0.5f, 0.5f, 0.5f, 1.0f};
  s.layers[0] = {OitLayer{{1, 0, 0, 0.5f}, {1.0f, 0.2f, 0.2f}, 0.2f}, OitLayer{{0, 1, 0, 0.4f}, {0.2f, 1.0f, 0.2f}, 0.5f},
                 OitLayer{{0, 0, 1, 0.6f}, {0.2f, 0.2f, 1.0f}, 0.8f}, OitLayer{{1, 1, 1, 0.3f}, {0.9f, 0.9f, 0.9f}, 0.35f}};
  return s;
}

namespace {

constexpr UINT kW = 4;
constexpr DXGI_FORMAT kAccum = DXGI_FORMAT_R16G16B16A16_FLOAT;
constexpr DXGI_FORMAT kReveal = DXGI_FORMAT_R8_UNORM;
constexpr DXGI_FORMAT kFrame = DXGI_FORMAT_R8G8B8A8_UNORM;

struct GpuLayer {  // the structured-buffer element, 48 bytes
  float color[4];
  float transmission[4];
  float depth, pad[3];
};

const char* kLayerVS = R"(
struct Layer { float4 color; float4 transmission; float4 depth; };
StructuredBuffer<Layer> Layers : register(t0);
struct V { float4 pos : SV_Position; nointerpolation uint id : LAYERID; };
V main(uint vid : SV_VertexID) {
  uint quad = vid / 6; uint corner = vid % 6;   // quad = layer * 16 + pixel
  uint pixel = quad % 16;
  float x = float(pixel % 4) + ((corner == 1 || corner == 4 || corner == 5) ? 1.0 : 0.0);
  float y = float(pixel / 4) + ((corner == 2 || corner == 3 || corner == 5) ? 1.0 : 0.0);
  V o; o.pos = float4(x / 2.0 - 1.0, 1.0 - y / 2.0, Layers[quad].depth.x, 1.0); o.id = quad; return o;
})";

// shaders_hlsl/oit/wboit_weight.hlsli, the one definition of Table 1's weight.
std::string WeightSource() { return ShaderSource("oit/wboit_weight.hlsli"); }

std::string AccumulatePS(bool colored) {
  std::string s = R"(
struct Layer { float4 color; float4 transmission; float4 depth; };
StructuredBuffer<Layer> Layers : register(t0);
)";
  s += WeightSource();
  s += "struct Out { float4 accum : SV_Target0; float4 reveal : SV_Target1;";
  if (colored) s += " float4 frame : SV_Target2;";
  s += R"( };
Out main(float4 pos : SV_Position, nointerpolation uint id : LAYERID) {
  Layer l = Layers[id];
  float a = l.color.a;
  float w = WboitWeight(a, pos.z);
  Out o;
  o.accum = float4(l.color.rgb * a, a) * w;
  o.reveal = float4(a, a, a, a);
)";
  if (colored) s += "  o.frame = float4(a * (1.0 - l.transmission.rgb), a);\n";
  s += "  return o;\n}\n";
  return s;
}

const char* kFullscreenVS = R"(float4 main(uint id : SV_VertexID) : SV_Position {
  float2 uv = float2((id << 1) & 2, id & 2);
  return float4(uv * float2(2, -2) + float2(-1, 1), 0, 1);
})";

const char* kComposePS = R"(
Texture2D<float4> Accum : register(t0);
Texture2D<float4> Reveal : register(t1);
float4 main(float4 pos : SV_Position) : SV_Target {
  int3 p = int3(pos.xy, 0);
  float4 accum = Accum.Load(p);
  float r = Reveal.Load(p).r;
  return float4(accum.rgb / max(accum.a, 0.0001), 1.0 - r);
})";

ref::StoredColor Unpack(DXGI_FORMAT f, const std::vector<uint8_t>& bytes, int pixel) {
  const size_t bpp = ref::BytesPerPixel(f);
  return ref::UnpackPixel(f, std::span<const uint8_t>(bytes.data() + pixel * bpp, bpp));
}

uint32_t MaxSteps(DXGI_FORMAT f, const ref::StoredColor& a, const ref::StoredColor& b, int channels = 4) {
  uint32_t m = 0;
  for (int c = 0; c < channels; ++c) m = std::max(m, ref::StoredDistance(f, c, a.bits[c], b.bits[c]));
  return m;
}

// The compose pass's source colour from stored accum / revealage, as the PS computes it.
ref::Float4 ComposeSource(const ref::StoredColor& accum, const ref::StoredColor& reveal) {
  const ref::Float4 a = ref::Decode(kAccum, accum);
  const float r = ref::Decode(kReveal, reveal)[0];
  const float d = std::max(a[3], 0.0001f);
  return {a[0] / d, a[1] / d, a[2] / d, 1.0f - r};
}

}  // namespace

OitTables LoadOitTables(Gpu& gpu, OitMethod method) {
  struct Source {
    const char* method;  // the registered method whose include holds the blocks
    const char* accumulate;
    const char* compose;
  };
  const Source source = method == OitMethod::Wboit ? Source{"wboit", "WboitAccumulate", "WboitCompose"}
                        : method == OitMethod::ColoredLiteral
                            ? Source{"colored-literal", "ColoredAccumulate", "ColoredComposeLiteral"}
                            : Source{"colored", "ColoredAccumulate", "ColoredCompose"};
  std::string error;
  ComPtr<fx::Effect> effect =
      renderer::oit::LoadMethodEffect(gpu.device(), *renderer::oit::FindMethod(source.method), nullptr, {}, &error);
  if (!effect) throw std::runtime_error(error);
  OitTables tables;
  if (effect->GetVariableByName(source.accumulate)->AsBlend()->GetBackingStore(0, &tables.accumulate) != S_OK ||
      effect->GetVariableByName(source.compose)->AsBlend()->GetBackingStore(0, &tables.compose) != S_OK)
    throw std::runtime_error(std::string("no blend states ") + source.accumulate + ", " + source.compose);
  return tables;
}

std::string ShaderSource(const std::string& file) {
  const std::string path = renderer::ShaderDirectory() + "/" + file;
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<float> RunFloatCompute(Gpu& gpu, const std::string& source, const void* inputs, UINT inputStride,
                                   UINT inputCount, UINT outputCount) {
  const std::vector<uint32_t> spirv = Gpu::Compile(source, "cs_5_0");
  Device* device = gpu.device();
  DeviceContext* ctx = gpu.context();
  ComPtr<ComputeShader> shader;
  ComPtr<Buffer> output, staging;
  ComPtr<UnorderedAccessView> uav;
  auto srv = gpu.StructuredSRV(inputs, inputStride, inputCount);
  BUFFER_DESC outputDesc{outputCount * 4, USAGE_DEFAULT, BIND_UNORDERED_ACCESS, 0, RESOURCE_MISC_BUFFER_STRUCTURED, 4};
  BUFFER_DESC stagingDesc{outputCount * 4, USAGE_STAGING, 0, CPU_ACCESS_READ, 0, 0};
  if (device->CreateComputeShader(spirv.data(), spirv.size() * 4, nullptr, shader.GetAddressOf()) != S_OK ||
      device->CreateBuffer(&outputDesc, nullptr, output.GetAddressOf()) != S_OK ||
      device->CreateUnorderedAccessView(output.Get(), nullptr, uav.GetAddressOf()) != S_OK ||
      device->CreateBuffer(&stagingDesc, nullptr, staging.GetAddressOf()) != S_OK)
    throw std::runtime_error("RunFloatCompute: creating the compute pass failed");
  ShaderResourceView* view = srv.Get();
  UnorderedAccessView* out = uav.Get();
  ctx->CSSetShader(shader.Get(), nullptr, 0);
  ctx->CSSetShaderResources(0, 1, &view);
  ctx->CSSetUnorderedAccessViews(0, 1, &out, nullptr);
  ctx->Dispatch(inputCount, 1, 1);
  ctx->ClearState();
  ctx->CopyResource(staging.Get(), output.Get());
  MAPPED_SUBRESOURCE mapped{};
  if (ctx->Map(staging.Get(), 0, MAP_READ, 0, &mapped) != S_OK) throw std::runtime_error("RunFloatCompute: Map failed");
  std::vector<float> values(static_cast<const float*>(mapped.pData),
                            static_cast<const float*>(mapped.pData) + outputCount);
  ctx->Unmap(staging.Get(), 0);
  return values;
}

std::vector<float> WboitWeights(Gpu& gpu, const std::vector<std::array<float, 2>>& alphaDepth) {
  const std::string cs = WeightSource() + R"(
StructuredBuffer<float2> Inputs : register(t0);
RWStructuredBuffer<float> Weights : register(u0);
[numthreads(1, 1, 1)] void main(uint3 id : SV_DispatchThreadID) { Weights[id.x] = WboitWeight(Inputs[id.x].x, Inputs[id.x].y); }
)";
  const UINT n = static_cast<UINT>(alphaDepth.size());
  return RunFloatCompute(gpu, cs, alphaDepth.data(), sizeof(float) * 2, n, n);
}

OitResult RunOitFixture(Gpu& gpu, OitMethod method, const OitScene& scene) {
  const bool colored = method != OitMethod::Wboit;
  const OitTables tables = LoadOitTables(gpu, method);
  const BLEND_DESC& accumulateDesc = tables.accumulate;
  const BLEND_DESC& composeDesc = tables.compose;
  DeviceContext* ctx = gpu.context();
  // The CPU model's weights: the GPU's evaluation of the one definition, per pixel and layer.
  std::vector<std::array<float, 2>> alphaDepth;
  for (int p = 0; p < kOitPixels; ++p)
    for (const OitLayer& l : scene.layers[p]) alphaDepth.push_back({l.color[3], l.depth});
  const std::vector<float> weights = WboitWeights(gpu, alphaDepth);
  auto weight = [&](int pixel, int layer) { return weights[pixel * kOitLayers + layer]; };

  // Targets.
  auto accum = gpu.Texture(kW, kW, kAccum, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE);
  auto reveal = gpu.Texture(kW, kW, kReveal, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE);
  auto frame = gpu.Texture(kW, kW, kFrame, BIND_RENDER_TARGET);
  auto depth = gpu.Texture(kW, kW, DXGI_FORMAT_D32_FLOAT, BIND_DEPTH_STENCIL);
  auto accumRtv = gpu.RTV(accum.Get()), revealRtv = gpu.RTV(reveal.Get()), frameRtv = gpu.RTV(frame.Get());
  ComPtr<DepthStencilView> dsv;
  if (gpu.device()->CreateDepthStencilView(depth.Get(), nullptr, dsv.GetAddressOf()) != S_OK)
    throw std::runtime_error("CreateDepthStencilView failed");
  auto accumSrv = gpu.SRV(accum.Get()), revealSrv = gpu.SRV(reveal.Get());

  std::vector<ref::StoredColor> background(kOitPixels);
  std::vector<uint8_t> frameBytes;
  for (int p = 0; p < kOitPixels; ++p) {
    background[p] = ref::Encode(kFrame, scene.background[p]);
    auto px = ref::PackPixel(kFrame, background[p]);
    frameBytes.insert(frameBytes.end(), px.begin(), px.end());
  }
  ctx->UpdateSubresource(frame.Get(), 0, nullptr, frameBytes.data(), kW * 4, 0);
  const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 0, 0, 0};
  ctx->ClearRenderTargetView(accumRtv.Get(), zero);
  ctx->ClearRenderTargetView(revealRtv.Get(), one);
  ctx->ClearDepthStencilView(dsv.Get(), CLEAR_DEPTH, 1.0f, 0);

  std::vector<GpuLayer> layers(kOitLayers * kOitPixels);
  for (int l = 0; l < kOitLayers; ++l)
    for (int p = 0; p < kOitPixels; ++p) {
      const OitLayer& s = scene.layers[p][l];
      GpuLayer& g = layers[l * kOitPixels + p];
      std::memcpy(g.color, s.color.data(), 16);
      g.transmission[0] = s.transmission[0];
      g.transmission[1] = s.transmission[1];
      g.transmission[2] = s.transmission[2];
      g.transmission[3] = 0;
      g.depth = s.depth;
      g.pad[0] = g.pad[1] = g.pad[2] = 0;
    }
  auto layerSrv = gpu.StructuredSRV(layers.data(), sizeof(GpuLayer), static_cast<UINT>(layers.size()));

  // 3D transparency pass: depth test on, writes off; culling off.
  auto vs = gpu.VS(kLayerVS);
  auto ps = gpu.PS(AccumulatePS(colored));
  ComPtr<BlendState> accumulateState, composeState;
  gpu.device()->CreateBlendState(&accumulateDesc, accumulateState.GetAddressOf());
  gpu.device()->CreateBlendState(&composeDesc, composeState.GetAddressOf());
  DEPTH_STENCIL_DESC dsDesc;
  dsDesc.DepthWriteMask = DEPTH_WRITE_MASK_ZERO;
  ComPtr<DepthStencilState> dsState;
  gpu.device()->CreateDepthStencilState(&dsDesc, dsState.GetAddressOf());
  RASTERIZER_DESC rsDesc;
  rsDesc.CullMode = CULL_NONE;
  ComPtr<RasterizerState> rsState;
  gpu.device()->CreateRasterizerState(&rsDesc, rsState.GetAddressOf());

  ctx->ClearState();
  ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx->VSSetShader(vs.Get(), nullptr, 0);
  ShaderResourceView* vsSrv[] = {layerSrv.Get()};
  ctx->VSSetShaderResources(0, 1, vsSrv);
  ctx->PSSetShaderResources(0, 1, vsSrv);
  ctx->PSSetShader(ps.Get(), nullptr, 0);
  ctx->RSSetState(rsState.Get());
  gpu.Viewport(kW, kW);
  RenderTargetView* rtvs[] = {accumRtv.Get(), revealRtv.Get(), frameRtv.Get()};
  ctx->OMSetRenderTargets(colored ? 3 : 2, rtvs, dsv.Get());
  ctx->OMSetBlendState(accumulateState.Get(), nullptr, DEFAULT_SAMPLE_MASK);
  ctx->OMSetDepthStencilState(dsState.Get(), 0);
  ctx->Draw(6 * kOitLayers * kOitPixels, 0);

  OitResult result{method};
  const std::vector<uint8_t> accumBytes = gpu.Read(accum.Get(), 8);
  const std::vector<uint8_t> revealBytes = gpu.Read(reveal.Get(), 1);
  const std::vector<uint8_t> frameAfter3d = gpu.Read(frame.Get(), 4);

  // 2D composing pass.
  auto fsvs = gpu.VS(kFullscreenVS);
  auto cps = gpu.PS(kComposePS);
  ctx->ClearState();
  ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx->VSSetShader(fsvs.Get(), nullptr, 0);
  ctx->PSSetShader(cps.Get(), nullptr, 0);
  RenderTargetView* frameOnly[] = {frameRtv.Get()};
  ctx->OMSetRenderTargets(1, frameOnly, nullptr);
  ShaderResourceView* srvs[] = {accumSrv.Get(), revealSrv.Get()};
  ctx->PSSetShaderResources(0, 2, srvs);
  ctx->OMSetBlendState(composeState.Get(), nullptr, DEFAULT_SAMPLE_MASK);
  gpu.Viewport(kW, kW);
  ctx->Draw(3, 0);
  ctx->ClearState();
  const std::vector<uint8_t> frameFinal = gpu.Read(frame.Get(), 4);

  // The CPU model of the same passes.
  const ref::Float4 unusedFactor{1, 1, 1, 1};
  for (int p = 0; p < kOitPixels; ++p) {
    OitPixelResult& r = result.pixels[p];
    ref::StoredColor a = ref::Encode(kAccum, {0, 0, 0, 0});
    ref::StoredColor rv = ref::Encode(kReveal, {1, 0, 0, 0});
    ref::StoredColor f = background[p];
    for (int l = 0; l < kOitLayers; ++l) {
      const OitLayer& s = scene.layers[p][l];
      const float al = s.color[3];
      // SV_Position.z = the viewport-transformed z of the quad: the layer's depth.
      const float w = weight(p, l);
      const ref::Float4 o0{s.color[0] * al * w, s.color[1] * al * w, s.color[2] * al * w, al * w};
      const ref::Float4 o1{al, al, al, al};
      a = ref::BlendResult(kAccum, accumulateDesc, 0, unusedFactor, o0, o0, a).stored;
      rv = ref::BlendResult(kReveal, accumulateDesc, 1, unusedFactor, o1, o1, rv).stored;
      if (colored) {
        const ref::Float4 o2{al * (1 - s.transmission[0]), al * (1 - s.transmission[1]), al * (1 - s.transmission[2]), al};
        f = ref::BlendResult(kFrame, accumulateDesc, 2, unusedFactor, o2, o2, f).stored;
      }
    }
    r.modelAccum = a;
    r.modelRevealage = rv;
    const ref::Float4 src = ComposeSource(a, rv);
    r.modelFrame = ref::BlendResult(kFrame, composeDesc, 0, unusedFactor, src, src, f).stored;

    r.gpuAccum = Unpack(kAccum, accumBytes, p);
    r.gpuRevealage = Unpack(kReveal, revealBytes, p);
    r.gpuFrame = Unpack(kFrame, frameFinal, p);
    const ref::Float4 gpuSrc = ComposeSource(r.gpuAccum, r.gpuRevealage);
    r.stageFrame = ref::BlendResult(kFrame, composeDesc, 0, unusedFactor, gpuSrc, gpuSrc,
                                    Unpack(kFrame, frameAfter3d, p)).stored;

    // Sorted back-to-front OVER of the same straight-alpha layers.
    std::array<OitLayer, kOitLayers> sorted = scene.layers[p];
    std::sort(sorted.begin(), sorted.end(), [](const OitLayer& x, const OitLayer& y) { return x.depth > y.depth; });
    std::vector<ref::Float4> farToNear;
    for (const OitLayer& s : sorted) farToNear.push_back(s.color);
    r.over = ref::CompositeBackToFront(kFrame, farToNear, background[p]);

    // The method's intent in double precision.
    double sumA = 0, prodA = 1, prodT[3] = {1, 1, 1}, sumC[3] = {0, 0, 0};
    for (int l = 0; l < kOitLayers; ++l) {
      const OitLayer& s = scene.layers[p][l];
      const double al = s.color[3], w = weight(p, l);
      sumA += al * w;
      prodA *= 1 - al;
      for (int c = 0; c < 3; ++c) {
        sumC[c] += s.color[c] * al * w;
        prodT[c] *= 1 - al * (1 - s.transmission[c]);
      }
    }
    const ref::Float4 bg = ref::Decode(kFrame, background[p]);
    for (int c = 0; c < 3; ++c) {
      const double avg = sumC[c] / std::max(sumA, 1e-4);
      r.intent[c] = static_cast<float>(colored ? bg[c] * prodT[c] + avg * (1 - prodA)
                                               : avg * (1 - prodA) + bg[c] * prodA);
    }

    result.accumSteps = std::max(result.accumSteps, MaxSteps(kAccum, r.modelAccum, r.gpuAccum));
    result.revealageSteps = std::max(result.revealageSteps, MaxSteps(kReveal, r.modelRevealage, r.gpuRevealage, 1));
    result.stageSteps = std::max(result.stageSteps, MaxSteps(kFrame, r.stageFrame, r.gpuFrame, 3));
    result.chainSteps = std::max(result.chainSteps, MaxSteps(kFrame, r.modelFrame, r.gpuFrame, 3));
    result.overSteps = std::max(result.overSteps, MaxSteps(kFrame, r.over, r.gpuFrame, 3));
    const ref::StoredColor intentStored = ref::Encode(kFrame, {r.intent[0], r.intent[1], r.intent[2], 1});
    result.intentSteps = std::max(result.intentSteps, MaxSteps(kFrame, intentStored, r.gpuFrame, 3));
  }
  result.validation = gpu.validation();
  result.refusals = gpu.refusals();
  return result;
}

}  // namespace conf
