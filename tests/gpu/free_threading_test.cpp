// The device is free-threaded, as ID3D11Device is: creation and release from
// many threads at once, with the state-object deduplication intact.
#include <array>
#include <atomic>
#include <bit>
#include <thread>
#include <vector>

#include "gpu_helpers.h"
#include "states/blend.h"
#include "states/depth_stencil.h"
#include "states/rasterizer.h"
#include "states/sampler.h"

namespace rhi_test {
namespace {

using namespace rhi;

constexpr int kThreads = 8;

// Four descs per state type; the fixture holds the first two of each for the
// whole test, the last two die and are created again concurrently.
std::array<BLEND_DESC, 4> BlendDescs() {
  std::array<BLEND_DESC, 4> descs{};
  descs[1].RenderTarget[0].BlendEnable = TRUE;
  descs[1].RenderTarget[0].SrcBlend = BLEND_SRC_ALPHA;
  descs[1].RenderTarget[0].DestBlend = BLEND_INV_SRC_ALPHA;
  descs[2].RenderTarget[0].RenderTargetWriteMask = COLOR_WRITE_ENABLE_RED;
  descs[3].AlphaToCoverageEnable = TRUE;
  return descs;
}

std::array<DEPTH_STENCIL_DESC, 4> DepthStencilDescs() {
  std::array<DEPTH_STENCIL_DESC, 4> descs{};
  descs[1].DepthEnable = FALSE;
  descs[2].DepthFunc = COMPARISON_GREATER;
  descs[3].DepthWriteMask = DEPTH_WRITE_MASK_ZERO;
  return descs;
}

std::array<RASTERIZER_DESC, 4> RasterizerDescs() {
  std::array<RASTERIZER_DESC, 4> descs{};
  descs[1].CullMode = CULL_NONE;
  descs[2].FillMode = FILL_WIREFRAME;
  descs[3].DepthBias = 7;
  return descs;
}

std::array<SAMPLER_DESC, 4> SamplerDescs() {
  std::array<SAMPLER_DESC, 4> descs{};
  descs[1].Filter = FILTER_MIN_MAG_MIP_POINT;
  descs[2].AddressU = TEXTURE_ADDRESS_WRAP;
  descs[3].MaxLOD = 3.0f;
  return descs;
}

// What a test thread checks of each creation: the held object where the
// fixture holds one, else an object reporting the normalised desc.
template <class State, class Desc>
struct Expected {
  std::array<ComPtr<State>, 4> held;
  std::array<Desc, 4> reported;
};

template <class State, class Desc, class Create>
Expected<State, Desc> HoldFirstTwo(Create create, const std::array<Desc, 4>& descs) {
  Expected<State, Desc> expected;
  for (int i = 0; i < 4; ++i) {
    ComPtr<State> state;
    EXPECT_EQ(create(&descs[i], state.GetAddressOf()), S_OK);
    state->GetDesc(&expected.reported[i]);
    if (i < 2) expected.held[i] = state;
  }
  return expected;
}

// Creates desc `i` and checks the object (see Expected). False on a mismatch.
template <class State, class Desc, class Create>
bool CreateAndCheck(Create create, const std::array<Desc, 4>& descs, const Expected<State, Desc>& expected, int i) {
  ComPtr<State> state;
  if (create(&descs[i], state.GetAddressOf()) != S_OK || !state) return false;
  if (expected.held[i]) return state.Get() == expected.held[i].Get();
  Desc reported;
  state->GetDesc(&reported);
  return rhi::states::RawEqual(reported, expected.reported[i]);
}

using FreeThreadingTest = RhiGpuTest;

TEST_F(FreeThreadingTest, EightThreadsCreateAndReleaseEveryKindOfObjectAndDeduplicationHolds) {
  const std::vector<uint32_t> vsCode = CompileHlsl(kColorVS, "main", "vs_5_0");
  const std::vector<uint32_t> psCode = CompileHlsl(kColorPS, "main", "ps_5_0");
  const INPUT_ELEMENT_DESC elements[] = {
      {"POSITION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
      {"COLOR", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0}};
  const auto blends = BlendDescs();
  const auto depthStencils = DepthStencilDescs();
  const auto rasterizers = RasterizerDescs();
  const auto samplers = SamplerDescs();
  auto createBlend = [&](const BLEND_DESC* d, BlendState** s) { return device->CreateBlendState(d, s); };
  auto createDepthStencil = [&](const DEPTH_STENCIL_DESC* d, DepthStencilState** s) {
    return device->CreateDepthStencilState(d, s);
  };
  auto createRasterizer = [&](const RASTERIZER_DESC* d, RasterizerState** s) {
    return device->CreateRasterizerState(d, s);
  };
  auto createSampler = [&](const SAMPLER_DESC* d, SamplerState** s) { return device->CreateSamplerState(d, s); };
  const auto heldBlends = HoldFirstTwo<BlendState>(createBlend, blends);
  const auto heldDepthStencils = HoldFirstTwo<DepthStencilState>(createDepthStencil, depthStencils);
  const auto heldRasterizers = HoldFirstTwo<RasterizerState>(createRasterizer, rasterizers);
  const auto heldSamplers = HoldFirstTwo<SamplerState>(createSampler, samplers);

  std::atomic<int> failures{0};
  auto check = [&](bool ok) {
    if (!ok) ++failures;
  };
  auto work = [&](int thread) {
    const uint32_t texels[16] = {};
    for (int iteration = 0; iteration < 60; ++iteration) {
      const int i = (thread + iteration) % 4;
      check(CreateAndCheck(createBlend, blends, heldBlends, i));
      check(CreateAndCheck(createDepthStencil, depthStencils, heldDepthStencils, i));
      check(CreateAndCheck(createRasterizer, rasterizers, heldRasterizers, i));
      check(CreateAndCheck(createSampler, samplers, heldSamplers, i));

      BUFFER_DESC bufferDesc{64, iteration % 2 ? USAGE_DYNAMIC : USAGE_IMMUTABLE, BIND_VERTEX_BUFFER,
                             iteration % 2 ? UINT(CPU_ACCESS_WRITE) : 0u, 0, 0};
      SUBRESOURCE_DATA bufferData{texels, 0, 0};
      ComPtr<Buffer> buffer;
      check(device->CreateBuffer(&bufferDesc, &bufferData, buffer.GetAddressOf()) == S_OK);

      TEXTURE2D_DESC textureDesc{2, 2, 1, 1, DXGI_FORMAT_R8G8B8A8_UNORM, {1, 0}, USAGE_DEFAULT,
                                 BIND_SHADER_RESOURCE | BIND_RENDER_TARGET, 0, 0};
      SUBRESOURCE_DATA textureData{texels, 8, 0};
      ComPtr<Texture2D> texture;
      check(device->CreateTexture2D(&textureDesc, &textureData, texture.GetAddressOf()) == S_OK);
      ComPtr<ShaderResourceView> srv;
      ComPtr<RenderTargetView> rtv;
      check(device->CreateShaderResourceView(texture.Get(), nullptr, srv.GetAddressOf()) == S_OK);
      check(device->CreateRenderTargetView(texture.Get(), nullptr, rtv.GetAddressOf()) == S_OK);

      ComPtr<VertexShader> vs;
      ComPtr<PixelShader> ps;
      ComPtr<InputLayout> layout;
      check(device->CreateVertexShader(vsCode.data(), vsCode.size() * 4, nullptr, vs.GetAddressOf()) == S_OK);
      check(device->CreatePixelShader(psCode.data(), psCode.size() * 4, nullptr, ps.GetAddressOf()) == S_OK);
      check(device->CreateInputLayout(elements, 2, vsCode.data(), vsCode.size() * 4, layout.GetAddressOf()) == S_OK);
      QUERY_DESC queryDesc{QUERY_OCCLUSION, 0};
      ComPtr<Query> query;
      check(device->CreateQuery(&queryDesc, query.GetAddressOf()) == S_OK);
    }
  };
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) threads.emplace_back(work, t);
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(failures.load(), 0);

  // Still one object per desc: the held ones, and for the others two creations meet.
  for (int i = 0; i < 4; ++i) {
    EXPECT_TRUE(CreateAndCheck(createBlend, blends, heldBlends, i));
    ComPtr<BlendState> a, b;
    ASSERT_EQ(device->CreateBlendState(&blends[i], a.GetAddressOf()), S_OK);
    ASSERT_EQ(device->CreateBlendState(&blends[i], b.GetAddressOf()), S_OK);
    EXPECT_EQ(a.Get(), b.Get());
    ComPtr<SamplerState> c, d;
    ASSERT_EQ(device->CreateSamplerState(&samplers[i], c.GetAddressOf()), S_OK);
    ASSERT_EQ(device->CreateSamplerState(&samplers[i], d.GetAddressOf()), S_OK);
    EXPECT_EQ(c.Get(), d.Get());
  }
  EXPECT_TRUE(Refusals().empty()) << Refusals().front();
}

// The case that crashed: a lookup found an object whose last Release was
// running and handed it out again.
TEST_F(FreeThreadingTest, TwoThreadsCreateAndReleaseTheSameBlendDesc200000Times) {
  BLEND_DESC desc;
  desc.RenderTarget[0].BlendEnable = TRUE;
  desc.RenderTarget[0].SrcBlend = BLEND_SRC_ALPHA;
  desc.RenderTarget[0].DestBlend = BLEND_INV_SRC_ALPHA;
  std::atomic<int> failures{0};
  auto work = [&] {
    for (int i = 0; i < 200000; ++i) {
      BlendState* state = nullptr;
      if (device->CreateBlendState(&desc, &state) != S_OK || !state) {
        ++failures;
        continue;
      }
      BLEND_DESC reported;
      state->GetDesc(&reported);
      if (reported.RenderTarget[0].SrcBlend != BLEND_SRC_ALPHA) ++failures;
      state->Release();
    }
  };
  std::thread first(work), second(work);
  first.join();
  second.join();
  EXPECT_EQ(failures.load(), 0);
}

// Found by tools/find_rasterizer_hash_collision.py 9a73e3a552fd36ca (the
// default SAMPLER_DESC's key hash): with one cache for every state type keyed
// by that hash, creating this rasterizer state and then the default sampler
// returned the rasterizer as a sampler.
RASTERIZER_DESC RasterizerWithTheDefaultSamplersHash() {
  RASTERIZER_DESC desc;
  desc.FillMode = FILL_SOLID;
  desc.CullMode = CULL_NONE;
  desc.FrontCounterClockwise = FALSE;
  desc.DepthBias = 299119928;
  desc.DepthBiasClamp = std::bit_cast<float>(0x053D127Eu);
  desc.SlopeScaledDepthBias = std::bit_cast<float>(0x07682BE2u);
  desc.DepthClipEnable = TRUE;
  return desc;
}

TEST_F(FreeThreadingTest, ARasterizerStateWithTheDefaultSamplersHashStaysARasterizerState) {
  const RASTERIZER_DESC rasterizerDesc = RasterizerWithTheDefaultSamplersHash();
  const SAMPLER_DESC samplerDesc;
  ASSERT_EQ(rhi::states::KeyHash(rasterizerDesc), rhi::states::KeyHash(samplerDesc)) << "the descs no longer collide";

  ComPtr<RasterizerState> rasterizer;
  ComPtr<SamplerState> sampler;
  ASSERT_EQ(device->CreateRasterizerState(&rasterizerDesc, rasterizer.GetAddressOf()), S_OK);
  ASSERT_EQ(device->CreateSamplerState(&samplerDesc, sampler.GetAddressOf()), S_OK);
  EXPECT_NE(static_cast<DeviceChild*>(rasterizer.Get()), static_cast<DeviceChild*>(sampler.Get()));
  RASTERIZER_DESC reportedRasterizer;
  rasterizer->GetDesc(&reportedRasterizer);
  EXPECT_TRUE(rhi::states::KeyEqual(reportedRasterizer, rasterizerDesc));
  SAMPLER_DESC reportedSampler;
  sampler->GetDesc(&reportedSampler);
  EXPECT_TRUE(rhi::states::KeyEqual(reportedSampler, samplerDesc));
  ComPtr<SamplerState> again;
  ASSERT_EQ(device->CreateSamplerState(&samplerDesc, again.GetAddressOf()), S_OK);
  EXPECT_EQ(again.Get(), sampler.Get());
}

}  // namespace
}  // namespace rhi_test
