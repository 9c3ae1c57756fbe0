// Multiple render targets, blend factor + sample mask at 4x MSAA, alpha-to-coverage.
#include <gtest/gtest.h>

#include "blend_matrix.h"
#include "conformance_gpu.h"
#include "rhi_reference/blend.h"
#include "rhi_reference/tolerance.h"

namespace {

using namespace rhi;
using conf::ComPtr;
using conf::Gpu;
namespace ref = rhi::reference;

constexpr DXGI_FORMAT kRgba8 = DXGI_FORMAT_R8G8B8A8_UNORM;
const char* kFullscreenVS = R"(float4 main(uint id : SV_VertexID) : SV_Position {
  float2 uv = float2((id << 1) & 2, id & 2);
  return float4(uv * float2(2, -2) + float2(-1, 1), 0, 1);
})";

void ExpectClean(Gpu& gpu) {
  for (const std::string& m : gpu.validation()) ADD_FAILURE() << "validation layer: " << m;
  for (const std::string& m : gpu.refusals()) ADD_FAILURE() << "refusal: " << m;
}

ref::StoredColor Rgba8(const std::vector<uint8_t>& bytes, size_t pixel) {
  return ref::UnpackPixel(kRgba8, std::span<const uint8_t>(bytes.data() + pixel * 4, 4));
}

// Per-sample contents of a 4x MSAA RGBA8 texture (W x H) as a 4W x H image: x = 4*px + sample.
std::vector<uint8_t> ReadSamples(Gpu& gpu, Texture2D* ms, UINT w, UINT h) {
  auto out = gpu.Texture(4 * w, h, kRgba8, BIND_RENDER_TARGET);
  auto rtv = gpu.RTV(out.Get());
  auto srv = gpu.SRV(ms);
  auto vs = gpu.VS(kFullscreenVS);
  auto ps = gpu.PS(R"(Texture2DMS<float4> T : register(t0);
    float4 main(float4 pos : SV_Position) : SV_Target { uint x = uint(pos.x); return T.Load(int2(x / 4, pos.y), x % 4); })");
  DeviceContext* ctx = gpu.context();
  ctx->ClearState();
  ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx->VSSetShader(vs.Get(), nullptr, 0);
  ctx->PSSetShader(ps.Get(), nullptr, 0);
  ShaderResourceView* srvs[] = {srv.Get()};
  ctx->PSSetShaderResources(0, 1, srvs);
  RenderTargetView* rtvs[] = {rtv.Get()};
  ctx->OMSetRenderTargets(1, rtvs, nullptr);
  gpu.Viewport(4 * w, h);
  ctx->Draw(3, 0);
  ctx->ClearState();
  return gpu.Read(out.Get(), 4);
}

// Eight targets, IndependentBlendEnable, a different blend and write mask on each.
TEST(OutputMerger, EightTargetsIndependentBlendAndWriteMasks) {
  Gpu gpu(nullptr, true);
  ASSERT_TRUE(gpu.ok());
  constexpr UINT kW = 4;
  BLEND_DESC desc;
  desc.IndependentBlendEnable = TRUE;
  const BLEND src[8] = {BLEND_ONE, BLEND_SRC_ALPHA, BLEND_ZERO, BLEND_DEST_COLOR,
                        BLEND_BLEND_FACTOR, BLEND_INV_SRC_COLOR, BLEND_SRC_ALPHA_SAT, BLEND_INV_DEST_ALPHA};
  const BLEND dst[8] = {BLEND_ONE, BLEND_INV_SRC_ALPHA, BLEND_SRC_COLOR, BLEND_ZERO,
                        BLEND_INV_BLEND_FACTOR, BLEND_ONE, BLEND_DEST_ALPHA, BLEND_SRC_ALPHA};
  const BLEND_OP ops[8] = {BLEND_OP_ADD, BLEND_OP_ADD, BLEND_OP_SUBTRACT, BLEND_OP_REV_SUBTRACT,
                           BLEND_OP_ADD, BLEND_OP_MIN, BLEND_OP_MAX, BLEND_OP_ADD};
  const UINT8 masks[8] = {0xF, 0x1, 0x2, 0x4, 0x8, 0x5, 0xA, 0x0};
  for (int i = 0; i < 8; ++i) {
    RENDER_TARGET_BLEND_DESC& rt = desc.RenderTarget[i];
    rt.BlendEnable = i == 7 ? FALSE : TRUE;  // target 7: blending off, nothing written (mask 0)
    rt.SrcBlend = src[i];
    rt.DestBlend = dst[i];
    rt.BlendOp = ops[i];
    rt.SrcBlendAlpha = i % 2 ? BLEND_SRC_ALPHA : BLEND_ONE;
    rt.DestBlendAlpha = i % 2 ? BLEND_INV_SRC_ALPHA : BLEND_ONE;
    rt.BlendOpAlpha = i % 3 ? BLEND_OP_ADD : BLEND_OP_SUBTRACT;
    rt.RenderTargetWriteMask = masks[i];
  }
  ComPtr<BlendState> state;
  ASSERT_EQ(gpu.device()->CreateBlendState(&desc, state.GetAddressOf()), S_OK);
  std::vector<ComPtr<Texture2D>> textures;
  std::vector<ComPtr<RenderTargetView>> rtvs;
  const ref::Float4 clear{0.2f, 0.4f, 0.6f, 0.8f};
  for (int i = 0; i < 8; ++i) {
    textures.push_back(gpu.Texture(kW, kW, kRgba8, BIND_RENDER_TARGET));
    rtvs.push_back(gpu.RTV(textures.back().Get()));
    gpu.context()->ClearRenderTargetView(rtvs.back().Get(), clear.data());
  }
  auto vs = gpu.VS(kFullscreenVS);
  // (An array output `float4 c[8] : SV_Target0` fails SPIR-V validation in the
  // HLSL front end - conflicting location 0 - so eight members are spelled out.)
  std::string psSource = "#define C(i) float4(0.1 * i, 0.5, 0.9 - 0.1 * i, 0.3 + 0.05 * i)\nstruct O {";
  for (int i = 0; i < 8; ++i) psSource += " float4 c" + std::to_string(i) + " : SV_Target" + std::to_string(i) + ";";
  psSource += " };\nO main() { O o;";
  for (int i = 0; i < 8; ++i) psSource += " o.c" + std::to_string(i) + " = C(" + std::to_string(i) + ");";
  psSource += " return o; }\n";
  auto ps = gpu.PS(psSource);
  DeviceContext* ctx = gpu.context();
  ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx->VSSetShader(vs.Get(), nullptr, 0);
  ctx->PSSetShader(ps.Get(), nullptr, 0);
  RenderTargetView* views[8];
  for (int i = 0; i < 8; ++i) views[i] = rtvs[i].Get();
  ctx->OMSetRenderTargets(8, views, nullptr);
  const ref::Float4 factor{0.25f, 0.5f, 0.75f, 0.6f};
  ctx->OMSetBlendState(state.Get(), factor.data(), DEFAULT_SAMPLE_MASK);
  gpu.Viewport(kW, kW);
  ctx->Draw(3, 0);
  ctx->ClearState();
  for (int i = 0; i < 8; ++i) {
    const ref::Float4 out{0.1f * i, 0.5f, 0.9f - 0.1f * i, 0.3f + 0.05f * i};
    const ref::StoredColor expected =
        ref::BlendResult(kRgba8, desc, i, factor, out, out, ref::Encode(kRgba8, clear)).stored;
    const ref::StoredColor actual = Rgba8(gpu.Read(textures[i].Get(), 4), 5);
    EXPECT_TRUE(ref::WithinTolerance(kRgba8, expected, actual))
        << "RT" << i << " expected " << expected.bits[0] << "," << expected.bits[1] << "," << expected.bits[2] << ","
        << expected.bits[3] << " got " << actual.bits[0] << "," << actual.bits[1] << "," << actual.bits[2] << ","
        << actual.bits[3];
  }
  ExpectClean(gpu);
}

// 4x MSAA, BLEND_FACTOR / INV_BLEND_FACTOR with factor (0.25, 0.5, 0.75, 1) and
// SampleMask 0b0101: samples 0 and 2 are blended, 1 and 3 keep the clear colour.
TEST(OutputMerger, BlendFactorAndSampleMaskAt4xMsaa) {
  Gpu gpu(nullptr, true);
  ASSERT_TRUE(gpu.ok());
  constexpr UINT kW = 4;
  auto ms = gpu.Texture(kW, kW, kRgba8, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE, 4);
  auto rtv = gpu.RTV(ms.Get());
  const ref::Float4 clear{0.8f, 0.6f, 0.4f, 0.2f};
  gpu.context()->ClearRenderTargetView(rtv.Get(), clear.data());
  BLEND_DESC desc;
  desc.RenderTarget[0].BlendEnable = TRUE;
  desc.RenderTarget[0].SrcBlend = desc.RenderTarget[0].SrcBlendAlpha = BLEND_BLEND_FACTOR;
  desc.RenderTarget[0].DestBlend = desc.RenderTarget[0].DestBlendAlpha = BLEND_INV_BLEND_FACTOR;
  ComPtr<BlendState> state;
  ASSERT_EQ(gpu.device()->CreateBlendState(&desc, state.GetAddressOf()), S_OK);
  auto vs = gpu.VS(kFullscreenVS);
  auto ps = gpu.PS("float4 main() : SV_Target { return float4(0.0, 1.0, 0.5, 1.0); }");
  DeviceContext* ctx = gpu.context();
  ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx->VSSetShader(vs.Get(), nullptr, 0);
  ctx->PSSetShader(ps.Get(), nullptr, 0);
  RenderTargetView* rtvs[] = {rtv.Get()};
  ctx->OMSetRenderTargets(1, rtvs, nullptr);
  const ref::Float4 factor{0.25f, 0.5f, 0.75f, 1.0f};
  ctx->OMSetBlendState(state.Get(), factor.data(), 0x5);
  gpu.Viewport(kW, kW);
  ctx->Draw(3, 0);
  ctx->ClearState();
  const std::vector<uint8_t> samples = ReadSamples(gpu, ms.Get(), kW, kW);
  const ref::StoredColor dest = ref::Encode(kRgba8, clear);
  const ref::StoredColor blended =
      ref::BlendResult(kRgba8, desc.RenderTarget[0], factor, {0, 1, 0.5f, 1}, {0, 1, 0.5f, 1}, dest).stored;
  for (UINT p = 0; p < kW * kW; ++p)
    for (UINT s = 0; s < 4; ++s) {
      const ref::StoredColor got = Rgba8(samples, p * 4 + s);
      const ref::StoredColor& want = (s % 2 == 0) ? blended : dest;
      EXPECT_TRUE(ref::WithinTolerance(kRgba8, want, got)) << "pixel " << p << " sample " << s << " got R " << got.bits[0]
                                                           << " want R " << want.bits[0];
    }
  ExpectClean(gpu);
}

// Alpha-to-coverage at 4x MSAA. D3D11 leaves the dither pattern to the
// implementation (FS 17.x: "the coverage mask is derived from alpha in an
// implementation-specific way"), so the rule tested is the part every
// implementation must share: alpha 0 covers no sample and alpha 1 every sample
// in every pixel, and the mean number of covered samples over the target never
// decreases as alpha grows (0, .25, .5, .75, 1). The means are printed.
TEST(OutputMerger, AlphaToCoverageEndpointsExactAndMonotonic) {
  Gpu gpu(nullptr, true);
  ASSERT_TRUE(gpu.ok());
  constexpr UINT kW = 8;
  BLEND_DESC desc;
  desc.AlphaToCoverageEnable = TRUE;
  ComPtr<BlendState> state;
  ASSERT_EQ(gpu.device()->CreateBlendState(&desc, state.GetAddressOf()), S_OK);
  auto vs = gpu.VS(kFullscreenVS);
  auto ps = gpu.PS("cbuffer A : register(b0) { float alpha; }; float4 main() : SV_Target { return float4(1, 1, 1, alpha); }");
  double previous = -1;
  for (float alpha : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) {
    auto ms = gpu.Texture(kW, kW, kRgba8, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE, 4);
    auto rtv = gpu.RTV(ms.Get());
    const float zero[4] = {0, 0, 0, 0};
    gpu.context()->ClearRenderTargetView(rtv.Get(), zero);
    auto cb = gpu.ConstantBuffer(&alpha, 4);
    DeviceContext* ctx = gpu.context();
    ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    ctx->VSSetShader(vs.Get(), nullptr, 0);
    ctx->PSSetShader(ps.Get(), nullptr, 0);
    Buffer* cbs[] = {cb.Get()};
    ctx->PSSetConstantBuffers(0, 1, cbs);
    RenderTargetView* rtvs[] = {rtv.Get()};
    ctx->OMSetRenderTargets(1, rtvs, nullptr);
    ctx->OMSetBlendState(state.Get(), nullptr, DEFAULT_SAMPLE_MASK);
    gpu.Viewport(kW, kW);
    ctx->Draw(3, 0);
    ctx->ClearState();
    const std::vector<uint8_t> samples = ReadSamples(gpu, ms.Get(), kW, kW);
    UINT total = 0;
    for (UINT p = 0; p < kW * kW; ++p) {
      UINT covered = 0;
      for (UINT s = 0; s < 4; ++s) covered += Rgba8(samples, p * 4 + s).bits[0] == 255;
      if (alpha == 0.0f) EXPECT_EQ(covered, 0u) << "pixel " << p;
      if (alpha == 1.0f) EXPECT_EQ(covered, 4u) << "pixel " << p;
      total += covered;
    }
    const double mean = double(total) / (kW * kW);
    std::printf("alpha %.2f: mean covered samples %.3f of 4\n", alpha, mean);
    EXPECT_GE(mean, previous) << "coverage decreased at alpha " << alpha;
    previous = mean;
  }
  ExpectClean(gpu);
}

}  // namespace
