// The family of transparency methods (renderer/oit) and scenes (renderer/scenes.h)
// through their registries: every method runs on every scene, its passes are
// the effect passes the trace shows, its memory is what its targets take, and
// what cannot be made is refused with the reason.
#include <set>
#include <utility>
#include <string>
#include <vector>

#include "gpu_test.h"
#include "renderer/translucency.h"
#include "renderer/oit/prefix_sum.h"
#include "rhi/trace.h"

namespace rhi_test {
namespace {

using renderer::Translucency;
using renderer::TranslucencySettings;
using renderer::oit::MethodInfo;

class MethodFamilyTest : public GpuTest {
 protected:
  std::unique_ptr<Translucency> Make(const char* scene, rhi::DeviceContext* ctx = nullptr,
                                    renderer::oit::FragmentSizing sizing = renderer::oit::FragmentSizing::Exact) {
    TranslucencySettings s;
    s.fragmentStorage.sizing = sizing;
    s.scene = scene;
    s.width = 40, s.height = 24;
    s.rule = {4, 2, 5, 5};
    s.shardCount = 20;
    std::string error;
    auto t = Translucency::Create(device.Get(), ctx ? ctx : context.Get(), s, &error);
    EXPECT_NE(t, nullptr) << error;
    return t;
  }
};

TEST_F(MethodFamilyTest, RegistriesHaveUniqueNamesThatFindTheirEntries) {
  std::set<std::string> names;
  for (const MethodInfo* m : renderer::oit::Methods()) {
    EXPECT_TRUE(names.insert(m->name).second) << m->name;
    EXPECT_EQ(renderer::oit::FindMethod(m->name), m);
    EXPECT_NE(std::string(m->include).find("oit/"), std::string::npos) << m->name;
    EXPECT_NE(m->create, nullptr);
  }
  EXPECT_EQ(renderer::oit::FindMethod("nope"), nullptr);
  for (const renderer::SceneInfo* s : renderer::Scenes()) EXPECT_EQ(renderer::FindScene(s->name), s);
  EXPECT_EQ(renderer::FindScene("nope"), nullptr);
}

TEST_F(MethodFamilyTest, NeedsAreDescribedInWords) {
  using namespace renderer::oit;
  EXPECT_EQ(DescribeNeeds(0), "nothing beyond D3D11.0");
  EXPECT_EQ(DescribeNeeds(kNeedsPixelShaderUavs | kNeedsMsaa), "pixel-shader UAVs, MSAA");
  EXPECT_EQ(DescribeNeeds(kNeedsFloat32Blend | kNeedsCompute), "float32 blending, compute");
  EXPECT_EQ(DescribeNeeds(kNeedsDualSourceBlend), "dual-source blending");
}

// Each method's passes, as Method::PassNames says, are the passes the frame applies
// after the opaque pass (forward or into the visibility buffer) and the object
// updates (their "technique/pass" markers).
TEST_F(MethodFamilyTest, EveryMethodAppliesThePassesItNames) {
  for (const char* scene : {"smoke", "shards"})
    for (const MethodInfo* method : renderer::oit::Methods()) {
      // The compute-tile methods name the four phases issue 19 times (Cull, Sort, Bin,
      // Blend), each several passes of the compute building blocks:
      // ComputeTilesTest.AppliesThePassesOfItsPhasesInOrder checks those.
      if (method->needs & renderer::oit::kNeedsQuadObjects) continue;
      SCOPED_TRACE(std::string(scene) + " " + method->name);
      rhi::Trace trace;
      ComPtr<rhi::DeviceContext> traced;
      ASSERT_EQ(rhi::CreateTracingContext(context.Get(), &trace, traced.GetAddressOf()), rhi::S_OK);
      auto t = Make(scene, traced.Get());
      ASSERT_TRUE(t);
      ASSERT_TRUE(t->RenderFrame(*method)) << t->error();
      // The frame's own opaque pass is the first Opaque/Scene; a method that draws the
      // backdrop into its own targets (oit::Backdrop) applies that pass again as its own.
      std::vector<std::string> passes;
      bool framesOpaquePass = true;
      for (const std::string& marker : trace.Filter({"SetMarker"})) {
        if (marker == "SetMarker(Update/StreamOut)" || marker == "SetMarker(Visibility/Ids)") continue;
        if (marker == "SetMarker(Opaque/Scene)" && std::exchange(framesOpaquePass, false)) continue;
        passes.push_back(marker.substr(marker.find('/') + 1, marker.size() - marker.find('/') - 2));
      }
      const renderer::oit::Method* instance = t->MethodInstance(*method);
      ASSERT_NE(instance, nullptr);
      EXPECT_EQ(passes, instance->PassNames());
      traced.Reset();
    }
}

// A method binds as D3D11's debug layer wants: no frame makes the runtime unbind a
// resource that is read and written at once (a hazard warning names the slot).
TEST_F(MethodFamilyTest, FramesRaiseNoHazardWarnings) {
  for (const renderer::SceneInfo* scene : renderer::Scenes())
    for (const MethodInfo* method : renderer::oit::Methods()) {
      auto t = Make(scene->name);
      ASSERT_TRUE(t);
      if (!t->Accepts(*method)) continue;  // the compute-tile methods draw particles only
      ClearMessages();
      for (int frame = 0; frame < 2; ++frame) ASSERT_TRUE(t->RenderFrame(*method)) << t->error();
      EXPECT_TRUE(Refusals().empty()) << scene->name << " " << method->name << ": " << Refusals().front();
    }
}

// Memory: the targets a method creates, computed here from their formats
// (accum R16G16B16A16_FLOAT: 8 bytes, revealage R8_UNORM: 1 byte per pixel).
// WBOIT with MSAA (document 001), 4 samples: opaque colour and accum
// R16G16B16A16_FLOAT (8 + 8), depth D32_FLOAT (4), product R16_FLOAT (2) and the
// composite R8G8B8A8 (4) per sample; per pixel instead of the composite, the three
// averaged targets (8 + 8 + 2 per pixel); the additive variants keep no product,
// the linear one an sRGB resolve (4 per pixel) besides.
// Depth peeling, N = 8 layers: two R32_TYPELESS depth buffers (4 bytes each) and
// per layer an R16G16B16A16_FLOAT colour and opacity (8 + 8), and the
// R32G32B32A32_FLOAT composite (16) the layers blend over. Dual depth
// peeling: two R32G32_FLOAT depth ranges (8 each), two front colours and two front
// opacities (R16G16B16A16_FLOAT, 8 each), one back colour and one back opacity (8 each),
// and the same composite.
TEST_F(MethodFamilyTest, MethodsReportTheMemoryOfTheirTargets) {
  auto t = Make("shards");
  ASSERT_TRUE(t);
  const uint64_t pixels = 40 * 24, layers = 8;
  const struct {
    const char* method;
    uint64_t bytes;
  } kExpected[] = {{"alpha", 0},
                   {"sorted", 0},
                   {"wboit", pixels * 9},
                   {"colored", pixels * 9},
                   {"colored-literal", pixels * 9},
                   {"wboit-msaa", pixels * 4 * (8 + 8 + 4 + 2 + 4)},
                   {"wboit-msaa-per-pixel", pixels * 4 * (8 + 8 + 4 + 2) + pixels * (8 + 8 + 2)},
                   {"wboit-msaa-additive", pixels * 4 * (8 + 8 + 4 + 4)},
                   {"wboit-msaa-linear", pixels * 4 * (8 + 8 + 4 + 4) + pixels * 4},
                   {"wboit-msaa-exposure", pixels * 4 * (8 + 8 + 4 + 4)},
                   // two depth buffers, a colour and an opacity layer (RGBA16F) each, the float32 composite
                   {"depth-peeling", pixels * (2 * 4 + layers * (8 + 8) + 16)},
                   {"dual-depth-peeling", pixels * (2 * 8 + 2 * 8 + 2 * 8 + 8 + 8 + 16)},
                   // a node pool of 16 a pixel (the default), 12 bytes a node, and a 4-byte head a pixel
                   {"linked-list", pixels * 16 * 12 + pixels * 4},
                   // document 003: b0 R32_FLOAT (4), b1..b4 R32G32B32A32_FLOAT (16), accum
                   // R16G16B16A16_FLOAT (8); the correction's nearest depth R32_FLOAT (4) or R16_FLOAT (2)
                   {"mboit", pixels * (4 + 16 + 8)},
                   {"moment-transparency", pixels * (4 + 16 + 8)},
                   {"moment-transparency-mindepth", pixels * (4 + 16 + 8 + 4)},
                   {"moment-transparency-mindepth-r16", pixels * (4 + 16 + 8 + 2)}};
  for (const auto& e : kExpected) {
    const MethodInfo* method = renderer::oit::FindMethod(e.method);
    ASSERT_NE(method, nullptr) << e.method;
    ASSERT_TRUE(t->RenderFrame(*method)) << t->error();
    EXPECT_EQ(t->MethodInstance(*method)->MemoryBytes(), e.bytes) << e.method;
  }
}

// prefix-sum: the fragment buffer (8 bytes a fragment; its first frame sized to 1.5x
// the frame's total, which the method read back), the per-pixel counts, offsets and
// cursors (4 bytes each), the total (4), and the scan's block sums: two words (the sums
// and their scan) per group of 512 at every level until one group remains.
// The fragment buffer holds the frame's total (exact sizing, the default) or, sized
// late, 1.5x it (the first frame has no earlier total: it is read back and grown).
TEST_F(MethodFamilyTest, PrefixSumReportsItsFragmentBufferAndPerPixelBuffers) {
  for (const bool exact : {true, false}) {
    auto t = Make("shards", nullptr, exact ? renderer::oit::FragmentSizing::Exact : renderer::oit::FragmentSizing::Late);
    ASSERT_TRUE(t);
    const MethodInfo& method = *renderer::oit::FindMethod("prefix-sum");
    ASSERT_TRUE(t->RenderFrame(method)) << t->error();
    const auto frame = renderer::oit::ReadPrefixSumFrame(*t->MethodInstance(method), context.Get());
    ASSERT_TRUE(frame);
    const uint64_t pixels = 40 * 24;
    uint64_t scanBytes = 0;
    for (uint64_t n = pixels;; n = (n + 511) / 512) {
      scanBytes += 2 * 4 * ((n + 511) / 512);
      if ((n + 511) / 512 == 1) break;
    }
    const uint64_t fragments = exact ? frame->total : frame->total + frame->total / 2;
    EXPECT_EQ(frame->capacity, fragments) << (exact ? "exact" : "late");
    EXPECT_EQ(t->MethodInstance(method)->MemoryBytes(), fragments * 8 + pixels * 12 + 4 + scanBytes)
        << (exact ? "exact" : "late");
  }
}

// A method whose pass no object's effect has: the frame is refused with the
// object, the method and the pass named, and the frame index does not advance.
class MissingPassMethod final : public renderer::oit::Method {
 public:
  void Render(const renderer::oit::RenderArgs& a) override {
    a.marks->BeginPass(0);
    a.geometry->Draw(a.context, "Peel", renderer::oit::DrawOrder::AsSubmitted);
  }
  uint64_t MemoryBytes() const override { return 0; }
  const std::vector<std::string>& PassNames() const override { return passes_; }

 private:
  std::vector<std::string> passes_{"Peel"};
};
std::unique_ptr<renderer::oit::Method> CreateMissingPass(const MethodInfo&, const renderer::oit::MethodSetup&,
                                                         std::string*) {
  return std::make_unique<MissingPassMethod>();
}

TEST_F(MethodFamilyTest, APassNoObjectHasIsRefusedWithTheReason) {
  const MethodInfo missing{"missing-pass", "oit/alpha.fxh", 0, renderer::oit::DrawOrder::AsSubmitted, "test",
                           CreateMissingPass};
  auto t = Make("shards");
  ASSERT_TRUE(t);
  EXPECT_FALSE(t->RenderFrame(missing));
  EXPECT_NE(t->error().find("shards.fx"), std::string::npos) << t->error();
  EXPECT_NE(t->error().find("Peel"), std::string::npos) << t->error();
  EXPECT_EQ(t->frame(), 0u);
}

// An include that does not exist: the effect's error (file:line:column) reaches error().
TEST_F(MethodFamilyTest, AMissingIncludeIsRefusedWithTheCompilersMessage) {
  const MethodInfo broken{"broken", "oit/no_such_method.fxh", 0, renderer::oit::DrawOrder::AsSubmitted, "test",
                          renderer::oit::FindMethod("alpha")->create};
  auto t = Make("shards");
  ASSERT_TRUE(t);
  EXPECT_FALSE(t->RenderFrame(broken));
  EXPECT_NE(t->error().find("shards.fx"), std::string::npos) << t->error();
  EXPECT_NE(t->error().find("no_such_method.fxh"), std::string::npos) << t->error();
}

TEST_F(MethodFamilyTest, AnUnknownSceneIsRefusedWithTheSceneNames) {
  TranslucencySettings s;
  s.scene = "no-such-scene";
  std::string error;
  EXPECT_EQ(Translucency::Create(device.Get(), context.Get(), s, &error), nullptr);
  EXPECT_NE(error.find("no-such-scene"), std::string::npos) << error;
  EXPECT_NE(error.find("smoke, fire, shards"), std::string::npos) << error;
}

}  // namespace
}  // namespace rhi_test
