// The frame order of document 000, checked on the recorded call trace
// (rhi/trace.h): for frames 0 and 1 of each demo and method, the passes
// (fx::EffectPass::Apply's SetMarker("technique/pass")) and the draw calls must
// follow the paper: opaque objects -> particle update pass (stream output;
// Draw(1,0) on the first frame, DrawAuto after) -> 3D transparency pass
// (DrawAuto of the particles / DrawIndexedInstanced of the shards) -> 2D
// composing pass. Also: the method includes' state blocks are Tables 1-4.
#include <cctype>
#include <string>
#include <vector>

#include "fx/effect.h"
#include "gpu_test.h"
#include "method_lookup.h"
#include "renderer/effect_files.h"
#include "renderer/translucency.h"
#include "rhi/trace.h"

namespace rhi_test {
namespace {

using renderer::Translucency;
using renderer::TranslucencySettings;
using renderer::oit::MethodInfo;

// Document 000's methods and the technique the paper's passes belong to (fire: OVER is additive).
struct PaperMethod {
  const char* method;
  const char* technique;
  bool composes;
};
constexpr PaperMethod kPaperMethods[] = {{"alpha", "Alpha", false},
                                         {"sorted", "Alpha", false},
                                         {"wboit", "Wboit", true},
                                         {"colored", "Colored", true},
                                         {"colored-literal", "ColoredLiteral", true}};

// The paper's sequence of passes and draws for one frame.
std::vector<std::string> PaperOrder(const std::string& scene, const PaperMethod& method, uint32_t frame,
                                    uint32_t emitters, uint32_t shards, uint64_t liveParticles) {
  const bool fireOver = scene == "fire" && std::string(method.technique) == "Alpha";
  const std::string t = fireOver ? "Fire" : method.technique;
  std::vector<std::string> order = {"SetMarker(Opaque/Scene)", "Draw(780, 0)"};  // the opaque scene: 780 vertices
  if (scene != "shards") {
    order.push_back("SetMarker(Update/StreamOut)");
    order.push_back(frame == 0 ? "Draw(" + std::to_string(emitters) + ", 0)" : "DrawAuto()");
    order.push_back("SetMarker(" + t + "/Transparency)");
    // The sorted reference draws the CPU-sorted copy, whose count it read back.
    order.push_back(std::string(method.method) == "sorted" ? "Draw(" + std::to_string(liveParticles) + ", 0)"
                                                           : "DrawAuto()");
  } else {
    order.push_back("SetMarker(" + t + "/Transparency)");
    order.push_back("DrawIndexedInstanced(36, " + std::to_string(shards) + ", 0, 0, 0)");  // 12 triangles a shard
  }
  if (method.composes) {
    order.push_back("SetMarker(" + t + "/Compose)");
    order.push_back("Draw(3, 0)");
  }
  return order;
}

class TraceTest : public GpuTest {};

TEST_F(TraceTest, PassesAndDrawsFollowThePapersFrameOrder) {
  for (const char* scene : {"smoke", "fire", "shards"})
    for (const PaperMethod& method : kPaperMethods) {
      TranslucencySettings s;
      s.scene = scene;
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
        ASSERT_TRUE(t->RenderFrame(Method(method.method))) << t->error();
        const auto got = trace.Filter({"SetMarker", "Draw", "DrawAuto", "DrawIndexedInstanced", "DrawInstanced",
                                       "DrawIndexed"});
        const auto want = PaperOrder(scene, method, frame, s.rule.emitters, s.shardCount, t->particleCount());
        EXPECT_EQ(got, want) << scene << " " << method.method << " frame " << frame
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
  ASSERT_TRUE(t->RenderFrame(Method("wboit"))) << t->error();
  trace.Clear();
  ASSERT_TRUE(t->RenderFrame(Method("wboit"))) << t->error();
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
  s.scene = "shards";
  s.width = 32, s.height = 18;
  s.shardCount = 10;
  std::string error;
  auto t = Translucency::Create(device.Get(), traced.Get(), s, &error);
  ASSERT_NE(t, nullptr) << error;
  ASSERT_TRUE(t->RenderFrame(Method("colored"))) << t->error();
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
  s.scene = "shards";
  s.width = 32, s.height = 18;
  s.shardCount = 10;
  std::string error;
  auto t = Translucency::Create(device.Get(), traced.Get(), s, &error);
  ASSERT_NE(t, nullptr) << error;
  traced->BeginEvent("frame 0");
  ASSERT_TRUE(t->RenderFrame(Method("wboit"))) << t->error();
  traced->SetMarker("after the frame");
  traced->EndEvent();
  const std::vector<std::string> want = {"BeginEvent(frame 0)",         "SetMarker(Opaque/Scene)",
                                         "SetMarker(Wboit/Transparency)", "SetMarker(Wboit/Compose)",
                                         "SetMarker(after the frame)",   "EndEvent()"};
  EXPECT_EQ(trace.Filter({"BeginEvent", "EndEvent", "SetMarker"}), want);
}

// ---------------------------------------------------------------------------
// The state blocks of the method includes (shaders_hlsl/oit/*.fxh, where the
// tables live) against SPEC.md's tables, row by row: each row restates a table
// of the document, the oracle, and is checked on the effect the renderer loads.

struct SpecBlendRow {
  const char* table;   // SPEC.md's name for it
  const char* method;  // the method whose effect holds the block
  const char* object;  // null: the method's own effect (oit/method.fx)
  const char* block;
  int target;
  rhi::BLEND src, dest, srcAlpha, destAlpha;  // BlendOp and BlendOpAlpha are ADD in every table
};

using enum rhi::BLEND;
const SpecBlendRow kSpecTables[] = {
    {"OVER", "alpha", nullptr, "Over", 0, BLEND_SRC_ALPHA, BLEND_INV_SRC_ALPHA, BLEND_ONE, BLEND_INV_SRC_ALPHA},
    {"fire: additive", "alpha", "smoke.fx", "Additive", 0, BLEND_SRC_ALPHA, BLEND_ONE, BLEND_ZERO, BLEND_ONE},
    {"Table 1 accum", "wboit", nullptr, "WboitAccumulate", 0, BLEND_ONE, BLEND_ONE, BLEND_ONE, BLEND_ONE},
    // D3D11 forbids colour factors for alpha; revealage is R8, so its alpha factors never matter.
    {"Table 1 revealage", "wboit", nullptr, "WboitAccumulate", 1, BLEND_ZERO, BLEND_INV_SRC_COLOR, BLEND_ZERO,
     BLEND_INV_SRC_ALPHA},
    {"Table 2", "wboit", nullptr, "WboitCompose", 0, BLEND_SRC_ALPHA, BLEND_INV_SRC_ALPHA, BLEND_SRC_ALPHA,
     BLEND_INV_SRC_ALPHA},
    {"Table 3 accum", "colored", nullptr, "ColoredAccumulate", 0, BLEND_ONE, BLEND_ONE, BLEND_ONE, BLEND_ONE},
    {"Table 3 revealage", "colored", nullptr, "ColoredAccumulate", 1, BLEND_ZERO, BLEND_INV_SRC_COLOR, BLEND_ZERO,
     BLEND_INV_SRC_ALPHA},
    // The table gives no alpha rule for the frame: kept (ZERO/ONE).
    {"Table 3 frame", "colored", nullptr, "ColoredAccumulate", 2, BLEND_ZERO, BLEND_INV_SRC_COLOR, BLEND_ZERO,
     BLEND_ONE},
    {"Table 4 corrected", "colored", nullptr, "ColoredCompose", 0, BLEND_SRC_ALPHA, BLEND_ONE, BLEND_ZERO, BLEND_ONE},
    {"Table 4 as printed", "colored-literal", nullptr, "ColoredComposeLiteral", 0, BLEND_INV_SRC_ALPHA, BLEND_ONE,
     BLEND_ZERO, BLEND_ONE},
    // Document 001 (SPEC.md "001"): glBlendFunci(0, ONE, ONE), glBlendFunci(1, DST_COLOR, ZERO);
    // the alpha factors of the R16_FLOAT product (no alpha) are DEST_ALPHA/ZERO.
    {"001 accum", "wboit-msaa", nullptr, "WboitMsaaAccumulate", 0, BLEND_ONE, BLEND_ONE, BLEND_ONE, BLEND_ONE},
    {"001 product", "wboit-msaa", nullptr, "WboitMsaaAccumulate", 1, BLEND_DEST_COLOR, BLEND_ZERO, BLEND_DEST_ALPHA,
     BLEND_ZERO},
    {"001 additive", "wboit-msaa-additive", nullptr, "AdditiveAccumulate", 0, BLEND_ONE, BLEND_ONE, BLEND_ONE,
     BLEND_ONE},
};

void PrintTo(const SpecBlendRow& row, std::ostream* os) { *os << row.table << " (" << row.block << ")"; }

class SpecTableTest : public GpuTest, public ::testing::WithParamInterface<SpecBlendRow> {};

TEST_P(SpecTableTest, TheEffectsStateBlockIsTheTable) {
  const SpecBlendRow& row = GetParam();
  std::string error;
  renderer::EffectDefines defines;
  if (row.object) defines.emplace_back("FIRE", "1");
  ComPtr<fx::Effect> e = renderer::oit::LoadMethodEffect(device.Get(), Method(row.method), row.object, defines, &error);
  ASSERT_TRUE(e) << error;
  rhi::BLEND_DESC d;
  ASSERT_EQ(e->GetVariableByName(row.block)->AsBlend()->GetBackingStore(0, &d), rhi::S_OK) << row.block;
  EXPECT_FALSE(d.AlphaToCoverageEnable);
  const rhi::RENDER_TARGET_BLEND_DESC& rt = d.RenderTarget[row.target];
  EXPECT_TRUE(rt.BlendEnable);
  EXPECT_EQ(rt.SrcBlend, row.src);
  EXPECT_EQ(rt.DestBlend, row.dest);
  EXPECT_EQ(rt.BlendOp, rhi::BLEND_OP_ADD);
  EXPECT_EQ(rt.SrcBlendAlpha, row.srcAlpha);
  EXPECT_EQ(rt.DestBlendAlpha, row.destAlpha);
  EXPECT_EQ(rt.BlendOpAlpha, rhi::BLEND_OP_ADD);
  EXPECT_EQ(rt.RenderTargetWriteMask, rhi::COLOR_WRITE_ENABLE_ALL);
  // FX11 starts every BlendState with IndependentBlendEnable TRUE: targets no table names do not blend.
  EXPECT_TRUE(d.IndependentBlendEnable);
  int enabled = 0;
  for (const auto& target : d.RenderTarget) enabled += target.BlendEnable ? 1 : 0;
  int rowsOfBlock = 0;
  for (const SpecBlendRow& other : kSpecTables)
    rowsOfBlock += std::string(other.block) == row.block && std::string(other.method) == row.method;
  EXPECT_EQ(enabled, rowsOfBlock) << "targets blending in " << row.block;
}

INSTANTIATE_TEST_SUITE_P(SpecTables, SpecTableTest, ::testing::ValuesIn(kSpecTables),
                         [](const ::testing::TestParamInfo<SpecBlendRow>& info) {
                           std::string name = info.param.table;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

// The 3D transparency pass tests depth but does not write it; composing uses none.
TEST_F(TraceTest, TranslucentPassesTestDepthWithoutWritingIt) {
  std::string error;
  ComPtr<fx::Effect> e = renderer::oit::LoadMethodEffect(device.Get(), Method("wboit"), nullptr, {}, &error);
  ASSERT_TRUE(e) << error;
  rhi::DEPTH_STENCIL_DESC d;
  ASSERT_EQ(e->GetVariableByName("DepthTestNoWrite")->AsDepthStencil()->GetBackingStore(0, &d), rhi::S_OK);
  EXPECT_EQ(d.DepthEnable, rhi::TRUE);
  EXPECT_EQ(d.DepthWriteMask, rhi::DEPTH_WRITE_MASK_ZERO);
  EXPECT_EQ(d.DepthFunc, rhi::COMPARISON_LESS);
  ASSERT_EQ(e->GetVariableByName("NoDepth")->AsDepthStencil()->GetBackingStore(0, &d), rhi::S_OK);
  EXPECT_EQ(d.DepthEnable, rhi::FALSE);
}

// Document 001's translucent pass: glDepthFunc(GL_LEQUAL), glDepthMask(GL_FALSE).
TEST_F(TraceTest, WboitMsaaTestsLessEqualWithoutWritingDepth) {
  std::string error;
  ComPtr<fx::Effect> e = renderer::oit::LoadMethodEffect(device.Get(), Method("wboit-msaa"), nullptr, {}, &error);
  ASSERT_TRUE(e) << error;
  rhi::DEPTH_STENCIL_DESC d;
  ASSERT_EQ(e->GetVariableByName("DepthTestLessEqualNoWrite")->AsDepthStencil()->GetBackingStore(0, &d), rhi::S_OK);
  EXPECT_EQ(d.DepthEnable, rhi::TRUE);
  EXPECT_EQ(d.DepthWriteMask, rhi::DEPTH_WRITE_MASK_ZERO);
  EXPECT_EQ(d.DepthFunc, rhi::COMPARISON_LESS_EQUAL);
}

}  // namespace
}  // namespace rhi_test
