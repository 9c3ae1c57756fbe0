// Effect passes whose pixel shader uses UAVs: Apply binds them through
// OMSetRenderTargetsAndUnorderedAccessViews, keeping the render targets, from
// the shader's lowest UAV register on (FX11); what cannot be bound is refused.
#include <algorithm>

#include "effect_test_util.h"

namespace effects_test {
namespace {

using rhi::ComPtr;

constexpr UINT kSize = 4;

// A full-screen triangle; the PS counts fragments per pixel (u1) and appends
// each pixel's index to a list (u2), the pattern of per-pixel linked lists.
constexpr const char* kCountingEffect = R"(
RWStructuredBuffer<uint> Counts : register(u1);
AppendStructuredBuffer<uint> Fragments : register(u2);
float4 VS(uint id : SV_VertexID) : SV_Position {
  return float4(id == 1 ? 3 : -1, id == 2 ? -3 : 1, 0.5, 1);
}
float4 PS(float4 pos : SV_Position) : SV_Target {
  uint index = uint(pos.y) * 4 + uint(pos.x);
  InterlockedAdd(Counts[index], 1);
  Fragments.Append(index);
  return float4(1, 1, 1, 1);
}
technique11 T {
  pass P { SetVertexShader(CompileShader(vs_5_0, VS())); SetPixelShader(CompileShader(ps_5_0, PS())); }
}
)";

class EffectUavTest : public EffectTest {
 protected:
  void SetUp() override {
    EffectTest::SetUp();
    if (HasFatalFailure()) return;
    target_ = MakeRenderTarget(kSize, kSize);
    rhi::RenderTargetView* rtvs[] = {target_.rtv.Get()};
    context->OMSetRenderTargets(1, rtvs, nullptr);
    SetViewport(kSize, kSize);
    context->IASetPrimitiveTopology(rhi::PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  }
  void SetUav(fx::Effect* effect, const char* name, rhi::UnorderedAccessView* uav) {
    ASSERT_EQ(effect->GetVariableByName(name)->AsUnorderedAccessView()->SetUnorderedAccessView(uav), rhi::S_OK);
  }
  rhi_test::GpuTest::Target target_;
};

TEST_F(EffectUavTest, PixelShaderUavsBindThroughTheOutputMerger) {
  auto effect = FromMemory(kCountingEffect);
  ASSERT_TRUE(effect);
  Rw counts = MakeRw(kSize * kSize);
  const UINT zero[4] = {};
  context->ClearUnorderedAccessViewUint(counts.uav.Get(), zero);
  Rw fragments = MakeRw(2 * kSize * kSize, rhi::BUFFER_UAV_FLAG_APPEND);
  SetUav(effect.Get(), "Counts", counts.uav.Get());
  SetUav(effect.Get(), "Fragments", fragments.uav.Get());
  fx::EffectPass* pass = effect->GetTechniqueByIndex(0)->GetPassByIndex(0);
  for (int draw = 0; draw < 2; ++draw) {
    ASSERT_EQ(pass->Apply(0, context.Get()), rhi::S_OK);
    context->Draw(3, 0);
  }
  EXPECT_EQ(ReadBufferAs<uint32_t>(counts.buffer.Get()), std::vector<uint32_t>(kSize * kSize, 2));
  // Apply keeps the hidden counter (initial count -1): the second draw appended after the first.
  const UINT sentinel = 0;
  ComPtr<rhi::Buffer> count = MakeBuffer(0, &sentinel, 4);
  context->CopyStructureCount(count.Get(), 0, fragments.uav.Get());
  EXPECT_EQ(ReadBufferAs<uint32_t>(count.Get())[0], 2 * kSize * kSize);
  std::vector<uint32_t> listed = ReadBufferAs<uint32_t>(fragments.buffer.Get()), expected;
  for (uint32_t i = 0; i < kSize * kSize; ++i) expected.insert(expected.end(), {i, i});
  std::sort(listed.begin(), listed.end());
  EXPECT_EQ(listed, expected);
  // The render target stayed bound (KEEP_RENDER_TARGETS_AND_DEPTH_STENCIL).
  const std::vector<uint8_t> pixels = ReadTexture(target_.texture.Get());
  EXPECT_TRUE(std::all_of(pixels.begin(), pixels.end(), [](uint8_t c) { return c == 255; }));
  EXPECT_TRUE(Refusals().empty()) << Refusals().front();
}

// u0 is render target 0's slot: the output merger refuses the pass's UAVs with the reason.
TEST_F(EffectUavTest, PixelShaderUavInRenderTargetSlotIsRefusedWithTheReason) {
  std::string source = kCountingEffect;
  source.replace(source.find("register(u1)"), 12, "register(u0)");
  auto effect = FromMemory(source);
  ASSERT_TRUE(effect);
  Rw counts = MakeRw(kSize * kSize);
  SetUav(effect.Get(), "Counts", counts.uav.Get());
  ASSERT_EQ(effect->GetTechniqueByIndex(0)->GetPassByIndex(0)->Apply(0, context.Get()), rhi::S_OK);
  EXPECT_TRUE(RefusedWith("OMSetRenderTargetsAndUnorderedAccessViews: UAVStartSlot (0) must be at least NumRTVs (1)"))
      << (Refusals().empty() ? "no refusal" : Refusals().front());
}

// What Apply could not bind fails the load instead of being skipped.
struct LoadRefusal {
  const char* name;
  const char* source;
  const char* reason;
};

class EffectUavLoadTest : public EffectTest, public ::testing::WithParamInterface<LoadRefusal> {};

TEST_P(EffectUavLoadTest, FailsWithTheReason) {
  fx::EFFECT_OPTIONS options;
  options.CacheDirectory = SuiteCache();
  options.Errors = &errors;
  ComPtr<fx::Effect> effect;
  const std::string source = GetParam().source;
  EXPECT_NE(fx::CreateEffectFromMemory(source.data(), source.size(), "test.fx", options, device.Get(),
                                       effect.GetAddressOf()),
            rhi::S_OK);
  EXPECT_NE(errors.find(GetParam().reason), std::string::npos) << errors;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, EffectUavLoadTest,
    ::testing::Values(
        LoadRefusal{"VertexShaderUav", R"(
RWStructuredBuffer<uint> Seen;
float4 VS(uint id : SV_VertexID) : SV_Position { Seen[id] = 1; return float4(0, 0, 0, 1); }
technique11 T { pass P { SetVertexShader(CompileShader(vs_5_0, VS())); SetPixelShader(NULL); } }
)",
                    "vs_5_0 VS: UAV 'Seen' (u0) cannot be bound: D3D11 binds UAVs to pixel and compute shaders only"},
        LoadRefusal{"RegisterPastU7", R"(
RWStructuredBuffer<uint> Far : register(u8);
float4 VS(uint id : SV_VertexID) : SV_Position { return float4(0, 0, 0, 1); }
float4 PS() : SV_Target { Far[0] = 1; return 0; }
technique11 T { pass P { SetVertexShader(CompileShader(vs_5_0, VS())); SetPixelShader(CompileShader(ps_5_0, PS())); } }
)",
                    "ps_5_0 PS: UAV 'Far' (u8) lies beyond u7, the last UAV register of feature level 11_0"}),
    [](const ::testing::TestParamInfo<LoadRefusal>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace effects_test
