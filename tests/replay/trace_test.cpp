// The frame order of document 000, checked on the recorded call trace
// (rhi/trace.h): for frames 0 and 1 of each demo and method, the passes
// (fx::EffectPass::Apply's SetMarker("technique/pass")) and the draw calls must
// follow the paper: opaque objects -> particle update pass (stream output;
// Draw(1,0) on the first frame, DrawAuto after) -> 3D transparency pass
// (DrawAuto of the particles / DrawIndexedInstanced of the shards) -> 2D
// composing pass. Also: the effect files' state blocks equal Tables 1-4.
#include <string>
#include <vector>

#include "fx/effect.h"
#include "gpu_test.h"
#include "renderer/oit_blend_tables.h"
#include "renderer/translucency.h"
#include "rhi/trace.h"

namespace rhi_test {
namespace {

using renderer::Translucency;
using renderer::TranslucencyDemo;
using renderer::TranslucencyMethod;
using renderer::TranslucencySettings;

constexpr TranslucencyMethod kMethods[4] = {TranslucencyMethod::Alpha, TranslucencyMethod::Wboit,
                                            TranslucencyMethod::Colored, TranslucencyMethod::Sorted};

const char* Technique(TranslucencyDemo demo, TranslucencyMethod method) {
  switch (method) {
    case TranslucencyMethod::Alpha:
    case TranslucencyMethod::Sorted: return demo == TranslucencyDemo::Fire ? "Fire" : "Alpha";
    case TranslucencyMethod::Wboit: return "Wboit";
    case TranslucencyMethod::Colored: return "Colored";
  }
  return "?";
}

// The paper's sequence of passes and draws for one frame.
std::vector<std::string> PaperOrder(TranslucencyDemo demo, TranslucencyMethod method, uint32_t frame,
                                    uint32_t emitters, uint32_t shards, uint64_t liveParticles) {
  const std::string t = Technique(demo, method);
  std::vector<std::string> order = {"SetMarker(Opaque/Scene)", "Draw(780, 0)"};  // the opaque scene: 780 vertices
  if (demo != TranslucencyDemo::Shards) {
    order.push_back("SetMarker(Update/StreamOut)");
    order.push_back(frame == 0 ? "Draw(" + std::to_string(emitters) + ", 0)" : "DrawAuto()");
    order.push_back("SetMarker(" + t + "/Transparency)");
    // The sorted reference draws the CPU-sorted copy, whose count it read back.
    order.push_back(method == TranslucencyMethod::Sorted ? "Draw(" + std::to_string(liveParticles) + ", 0)"
                                                         : "DrawAuto()");
  } else {
    order.push_back("SetMarker(" + t + "/Transparency)");
    order.push_back("DrawIndexedInstanced(36, " + std::to_string(shards) + ", 0, 0, 0)");  // 12 triangles a shard
  }
  if (method == TranslucencyMethod::Wboit || method == TranslucencyMethod::Colored) {
    order.push_back("SetMarker(" + t + "/Compose)");
    order.push_back("Draw(3, 0)");
  }
  return order;
}

class TraceTest : public GpuTest {};

TEST_F(TraceTest, PassesAndDrawsFollowThePapersFrameOrder) {
  for (TranslucencyDemo demo : {TranslucencyDemo::Smoke, TranslucencyDemo::Fire, TranslucencyDemo::Shards})
    for (TranslucencyMethod method : kMethods) {
      TranslucencySettings s;
      s.demo = demo;
      s.width = 64, s.height = 36;
      s.rule = {1, 4, 10, 5};  // the paper's init buffer: one emitter, so the first update is Draw(1, 0)
      s.shardCount = 50;
      rhi::Trace trace;
      ComPtr<rhi::DeviceContext> traced;
      ASSERT_EQ(rhi::CreateTracingContext(context.Get(), &trace, traced.GetAddressOf()), rhi::S_OK);
      std::string error;
      auto t = Translucency::Create(device.Get(), traced.Get(), s, &error);
      ASSERT_NE(t, nullptr) << error;
      for (uint32_t frame = 0; frame < 2; ++frame) {
        trace.Clear();
        t->RenderFrame(method);
        const auto got = trace.Filter({"SetMarker", "Draw", "DrawAuto", "DrawIndexedInstanced", "DrawInstanced",
                                       "DrawIndexed"});
        const auto want = PaperOrder(demo, method, frame, s.rule.emitters, s.shardCount, t->particleCount());
        EXPECT_EQ(got, want) << renderer::ToString(demo) << " " << renderer::ToString(method) << " frame " << frame
                             << "\nfull trace:\n"
                             << trace.ToString();
      }
      traced.Reset();
    }
}

TEST_F(TraceTest, StreamOutTargetsAreSetAroundTheUpdateDrawOnly) {
  TranslucencySettings s;
  s.width = 64, s.height = 36;
  s.rule = {1, 4, 10, 5};
  rhi::Trace trace;
  ComPtr<rhi::DeviceContext> traced;
  ASSERT_EQ(rhi::CreateTracingContext(context.Get(), &trace, traced.GetAddressOf()), rhi::S_OK);
  std::string error;
  auto t = Translucency::Create(device.Get(), traced.Get(), s, &error);
  ASSERT_NE(t, nullptr) << error;
  t->RenderFrame(TranslucencyMethod::Wboit);
  trace.Clear();
  t->RenderFrame(TranslucencyMethod::Wboit);
  const auto got = trace.Filter({"SOSetTargets", "SetMarker", "DrawAuto"});
  const std::vector<std::string> want = {"SetMarker(Opaque/Scene)", "SOSetTargets(1, obj/0)",
                                         "SetMarker(Update/StreamOut)", "DrawAuto()", "SOSetTargets(0)",
                                         "SetMarker(Wboit/Transparency)", "DrawAuto()", "SetMarker(Wboit/Compose)"};
  EXPECT_EQ(got, want) << trace.ToString();
}

TEST_F(TraceTest, ADisabledTraceForwardsWithoutRecording) {
  rhi::Trace trace;
  trace.enabled = false;
  ComPtr<rhi::DeviceContext> traced;
  ASSERT_EQ(rhi::CreateTracingContext(context.Get(), &trace, traced.GetAddressOf()), rhi::S_OK);
  TranslucencySettings s;
  s.demo = TranslucencyDemo::Shards;
  s.width = 32, s.height = 18;
  s.shardCount = 10;
  std::string error;
  auto t = Translucency::Create(device.Get(), traced.Get(), s, &error);
  ASSERT_NE(t, nullptr) << error;
  t->RenderFrame(TranslucencyMethod::Colored);
  EXPECT_TRUE(trace.calls.empty());
  EXPECT_FALSE(t->ReadFrame().empty());
  EXPECT_EQ(rhi::CreateTracingContext(nullptr, &trace, traced.ReleaseAndGetAddressOf()), rhi::E_INVALIDARG);
}

// BeginEvent / EndEvent / SetMarker reach the real context (debug-utils labels: the fixture
// enables the validation layer and so VK_EXT_debug_utils; any validation message fails the
// test) and the trace records them in order around the passes.
TEST_F(TraceTest, AnnotationsAreForwardedAndRecorded) {
  rhi::Trace trace;
  ComPtr<rhi::DeviceContext> traced;
  ASSERT_EQ(rhi::CreateTracingContext(context.Get(), &trace, traced.GetAddressOf()), rhi::S_OK);
  TranslucencySettings s;
  s.demo = TranslucencyDemo::Shards;
  s.width = 32, s.height = 18;
  s.shardCount = 10;
  std::string error;
  auto t = Translucency::Create(device.Get(), traced.Get(), s, &error);
  ASSERT_NE(t, nullptr) << error;
  traced->BeginEvent("frame 0");
  t->RenderFrame(TranslucencyMethod::Wboit);
  traced->SetMarker("after the frame");
  traced->EndEvent();
  const std::vector<std::string> want = {"BeginEvent(frame 0)",         "SetMarker(Opaque/Scene)",
                                         "SetMarker(Wboit/Transparency)", "SetMarker(Wboit/Compose)",
                                         "SetMarker(after the frame)",   "EndEvent()"};
  EXPECT_EQ(trace.Filter({"BeginEvent", "EndEvent", "SetMarker"}), want);
}

// ---------------------------------------------------------------------------
// The state blocks of shaders_hlsl/translucency_states.fxh against the tables.

void ExpectSameBlend(const rhi::BLEND_DESC& fx, const rhi::BLEND_DESC& table, const char* name) {
  EXPECT_EQ(fx.AlphaToCoverageEnable, table.AlphaToCoverageEnable) << name;
  // FX11 starts every BlendState with IndependentBlendEnable TRUE; the tables set it
  // only when targets differ. With every other target disabled both blend alike.
  for (int i = 0; i < 8; ++i) {
    const auto &a = fx.RenderTarget[i], &b = table.RenderTarget[i];
    SCOPED_TRACE(std::string(name) + " RT" + std::to_string(i));
    EXPECT_EQ(a.BlendEnable, b.BlendEnable);
    if (!b.BlendEnable) continue;
    EXPECT_EQ(a.SrcBlend, b.SrcBlend);
    EXPECT_EQ(a.DestBlend, b.DestBlend);
    EXPECT_EQ(a.BlendOp, b.BlendOp);
    EXPECT_EQ(a.SrcBlendAlpha, b.SrcBlendAlpha);
    EXPECT_EQ(a.DestBlendAlpha, b.DestBlendAlpha);
    EXPECT_EQ(a.BlendOpAlpha, b.BlendOpAlpha);
    EXPECT_EQ(a.RenderTargetWriteMask, b.RenderTargetWriteMask);
  }
}

TEST_F(TraceTest, EffectStateBlocksAreTheSpecTables) {
  for (const char* file : {"smoke.fx", "shards.fx"}) {
    fx::EFFECT_OPTIONS options;
    options.IncludeDirs = {PROJECT_SOURCE_ROOT "/shaders_hlsl"};
    std::string errors;
    options.Errors = &errors;
    ComPtr<fx::Effect> e;
    ASSERT_EQ(fx::CreateEffectFromFile((std::string(PROJECT_SOURCE_ROOT "/shaders_hlsl/") + file).c_str(), options,
                                       device.Get(), e.GetAddressOf()),
              rhi::S_OK)
        << errors;
    auto blend = [&](const char* name) {
      rhi::BLEND_DESC d;
      EXPECT_EQ(e->GetVariableByName(name)->AsBlend()->GetBackingStore(0, &d), rhi::S_OK) << name;
      return d;
    };
    ExpectSameBlend(blend("WboitAccumulate"), oit::WboitAccumulateBlend(), "Table 1");
    ExpectSameBlend(blend("WboitCompose"), oit::WboitComposeBlend(), "Table 2");
    ExpectSameBlend(blend("ColoredAccumulate"), oit::ColoredAccumulateBlend(), "Table 3");
    ExpectSameBlend(blend("ColoredCompose"), oit::ColoredComposeBlendCorrected(), "Table 4 corrected");
    ExpectSameBlend(blend("ColoredComposeLiteral"), oit::ColoredComposeBlendLiteral(), "Table 4 as printed");
    rhi::BLEND_DESC over;
    over.RenderTarget[0] =
        oit::TargetBlend(rhi::BLEND_SRC_ALPHA, rhi::BLEND_INV_SRC_ALPHA, rhi::BLEND_ONE, rhi::BLEND_INV_SRC_ALPHA);
    ExpectSameBlend(blend("Over"), over, "OVER");
    rhi::BLEND_DESC additive;
    additive.RenderTarget[0] = oit::TargetBlend(rhi::BLEND_SRC_ALPHA, rhi::BLEND_ONE, rhi::BLEND_ZERO, rhi::BLEND_ONE);
    ExpectSameBlend(blend("Additive"), additive, "additive (fire)");
    // The 3D transparency pass tests depth but does not write it; composing uses none.
    rhi::DEPTH_STENCIL_DESC d;
    ASSERT_EQ(e->GetVariableByName("DepthTestNoWrite")->AsDepthStencil()->GetBackingStore(0, &d), rhi::S_OK);
    EXPECT_EQ(d.DepthEnable, rhi::TRUE);
    EXPECT_EQ(d.DepthWriteMask, rhi::DEPTH_WRITE_MASK_ZERO);
    EXPECT_EQ(d.DepthFunc, rhi::COMPARISON_LESS);
    ASSERT_EQ(e->GetVariableByName("NoDepth")->AsDepthStencil()->GetBackingStore(0, &d), rhi::S_OK);
    EXPECT_EQ(d.DepthEnable, rhi::FALSE);
  }
}

}  // namespace
}  // namespace rhi_test
