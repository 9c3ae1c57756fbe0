// Depth peeling and dual depth peeling (document 002; renderer/src/oit/depth_peeling.cpp,
// dual_depth_peeling.cpp) against computations that do not use them:
//  - no fragment is lost or peeled twice: the pixels of all layers (an occlusion
//    query around each layer's composite pass, which discards the pixels the layer
//    does not hold) add up to what one plain pass, depth-tested against the opaque
//    depth as every layer is, counts (an occlusion query around `alpha`'s pass), on
//    scenes of known depth complexity (the complexity stack: exactly its quad count
//    at the centre) and on the teapot and the shards. Not on the smoke: its
//    billboards' corners have opacity 0 and take no layer, and the children an
//    emitter spawns in one update start at its centre, so that their billboards
//    coincide and share a layer (document 002 peels depth layers, not fragments);
//  - with enough layers depth peeling equals `sorted` where `sorted` is exact: the
//    complexity scene, whose quads are parallel, face the eye and lie at distinct
//    depths, so that sorting them by object is sorting every pixel's fragments (the
//    teapot's and the shards' triangles intersect or overlap cyclically, smoke
//    billboards turn to the eye and can cut each other: `sorted` is not exact there);
//  - dual depth peeling equals depth peeling with the same layers, where those are
//    all the layers (then both are the exact composite), with plain (complexity) and
//    coloured (shards) transmission. Where a partial composite exceeds 1 the RGBA8
//    frame clamps it, after every layer for depth peeling and only behind the front
//    for dual peeling (its front sums in float): 40 shards stay below that; at 600
//    a red shard (it lets all red through and adds its own) takes a pixel's red past
//    1 behind blue ones and the two differ there by up to 70 steps, as they should;
//  - a layer shown alone is the k-th nearest quad over grey, computed on the CPU;
//  - "until a layer is empty": the frame after one whose layer k was empty peels
//    layers 0..k only, and gives the same image.
// Images are compared per RGB channel: "within 1/255" is at most one 8-bit step.
#include <algorithm>
#include <numeric>

#include "gpu_test.h"
#include "method_lookup.h"
#include "renderer/meshes.h"
#include "renderer/translucency.h"
#include "rhi/trace.h"

namespace rhi_test {
namespace {

using renderer::Translucency;
using renderer::TranslucencySettings;
using renderer::oit::MethodInfo;

// One plain pass that counts the translucent samples in front of the opaque depth:
// `alpha`'s pass (LESS against the opaque depth, no depth writes) in an occlusion query.
class CountingMethod final : public renderer::oit::Method {
 public:
  explicit CountingMethod(rhi::Device* device) {
    const rhi::QUERY_DESC occlusion{rhi::QUERY_OCCLUSION, 0};
    device->CreateQuery(&occlusion, query_.GetAddressOf());
  }
  void Render(const renderer::oit::RenderArgs& a) override {
    a.marks->BeginPass(0);
    rhi::RenderTargetView* frame = a.targets.frame;
    a.context->OMSetRenderTargets(1, &frame, a.targets.depth);
    a.context->Begin(query_.Get());
    a.geometry->Draw(a.context, "Transparency", renderer::oit::DrawOrder::AsSubmitted);
    a.context->End(query_.Get());
  }
  uint64_t MemoryBytes() const override { return 0; }
  const std::vector<std::string>& PassNames() const override { return passes_; }
  uint64_t Samples(rhi::DeviceContext* context) const {
    uint64_t samples = 0;
    EXPECT_EQ(rhi::WaitForData(context, query_.Get(), &samples), rhi::S_OK);
    return samples;
  }

 private:
  ComPtr<rhi::Query> query_;
  std::vector<std::string> passes_{"Transparency"};
};
std::unique_ptr<renderer::oit::Method> CreateCounting(const MethodInfo&, const renderer::oit::MethodSetup& setup,
                                                      std::string*) {
  return std::make_unique<CountingMethod>(setup.device);
}
const MethodInfo kCounting{"counting", "oit/alpha.fxh", 0, renderer::oit::DrawOrder::AsSubmitted,
                           "test: counts the translucent samples", CreateCounting};

// The largest difference of two RGBA8 images over RGB, in 8-bit steps.
int MaxChannelDifference(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  EXPECT_EQ(a.size(), b.size());
  int most = 0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i)
    if (i % 4 != 3) most = std::max(most, std::abs(int(a[i]) - int(b[i])));
  return most;
}

class PeelingTest : public GpuTest {
 protected:
  static TranslucencySettings Settings(const char* scene) {
    TranslucencySettings s;
    s.scene = scene;
    s.width = 96, s.height = 54;
    s.shardCount = 40;
    return s;
  }
  std::unique_ptr<Translucency> Replay(const TranslucencySettings& s, const MethodInfo& method) {
    std::string error;
    auto t = Translucency::Create(device.Get(), context.Get(), s, &error);
    EXPECT_NE(t, nullptr) << error;
    if (t) {
      EXPECT_TRUE(t->RenderFrame(method)) << t->error();
    }
    return t;
  }
  std::vector<uint8_t> Render(const TranslucencySettings& s, const MethodInfo& method) {
    auto t = Replay(s, method);
    return t ? t->ReadFrame() : std::vector<uint8_t>{};
  }
  std::vector<uint64_t> LayerSamples(const TranslucencySettings& s) {
    auto t = Replay(s, Method("depth-peeling"));
    return t ? t->MethodInstance(Method("depth-peeling"))->LayerSamples(context.Get()) : std::vector<uint64_t>{};
  }
};

class LayerCountTest : public PeelingTest, public ::testing::WithParamInterface<const char*> {};

// Layer k holds the pixels with more than k fragments, so the counts never grow;
// the last of 64 layers is empty, so every fragment is in one of them.
TEST_P(LayerCountTest, TheLayersHoldEveryFragmentOnce) {
  TranslucencySettings s = Settings(GetParam());
  s.peelLayers = 64;
  auto counting = Replay(s, kCounting);
  ASSERT_TRUE(counting);
  const uint64_t fragments =
      static_cast<const CountingMethod*>(counting->MethodInstance(kCounting))->Samples(context.Get());
  const std::vector<uint64_t> layers = LayerSamples(s);
  ASSERT_EQ(layers.size(), 64u);
  EXPECT_EQ(layers.back(), 0u) << "64 layers are all the layers";
  for (size_t k = 1; k < layers.size(); ++k) EXPECT_LE(layers[k], layers[k - 1]) << "layer " << k;
  EXPECT_GT(layers[1], 0u) << "fragments behind fragments: something to peel";
  EXPECT_EQ(std::accumulate(layers.begin(), layers.end(), uint64_t(0)), fragments);
}

INSTANTIATE_TEST_SUITE_P(Scenes, LayerCountTest, ::testing::Values("complexity", "teapot", "shards"));

// The complexity stack's depth complexity is its quad count, reached at the centre.
TEST_F(PeelingTest, TheComplexityStackHasAsManyLayersAsQuads) {
  for (uint32_t quads : {1u, 5u, 12u}) {
    TranslucencySettings s = Settings("complexity");
    s.depthComplexity = quads;
    s.peelLayers = 16;
    const std::vector<uint64_t> layers = LayerSamples(s);
    ASSERT_EQ(layers.size(), 16u);
    const auto filled = std::count_if(layers.begin(), layers.end(), [](uint64_t n) { return n > 0; });
    EXPECT_EQ(filled, quads);
  }
}

class SortedTest : public PeelingTest, public ::testing::WithParamInterface<uint32_t> {};

// Enough layers (8, the default, for up to 8 quads): `sorted`'s OVER back to front.
// Depth peeling composites in float32 and rounds once; `sorted` rounds the 8-bit
// frame after each of its n blends, by at most half a step each, and the surfaces
// in front scale those errors by their transmission (at most 1): at most n / 2
// steps apart, plus one for the final rounding.
TEST_P(SortedTest, DepthPeelingEqualsSortedWhereSortingIsExact) {
  TranslucencySettings s = Settings("complexity");
  const uint32_t n = GetParam();
  s.depthComplexity = n;
  EXPECT_LE(MaxChannelDifference(Render(s, Method("depth-peeling")), Render(s, Method("sorted"))), int(n / 2 + 1));
}

INSTANTIATE_TEST_SUITE_P(DepthComplexity, SortedTest, ::testing::Values(1u, 3u, 8u));

// One layer (a one-slice array): the nearest quad over the lit grey wall, at the
// centre, lit as meshes.fx and scene.fx light them (ambient 0.45 plus Lambert).
TEST_F(PeelingTest, OneLayerIsTheNearestQuadOverTheWall) {
  TranslucencySettings s = Settings("complexity");
  s.peelLayers = 1;
  const std::vector<uint8_t> image = Render(s, Method("depth-peeling"));
  ASSERT_FALSE(image.empty());
  const renderer::QuadStack stack = renderer::ComplexityQuadStack(s);
  const std::vector<renderer::TriangleMesh> quads = renderer::CameraFacingQuads(stack);
  const glm::vec3 forward = glm::normalize(stack.target - stack.eye);
  const renderer::TriangleMesh& nearest =
      *std::min_element(quads.begin(), quads.end(), [&](const auto& a, const auto& b) {
        return glm::dot(a.positions[0] - stack.eye, forward) < glm::dot(b.positions[0] - stack.eye, forward);
      });
  const float lit = 0.45f + 0.55f * std::max(0.0f, glm::dot(nearest.normals[0], renderer::SceneLightDirection()));
  const float a = nearest.material.opacity;
  const glm::vec3 wall = glm::round(glm::vec3(0.5f * lit * 255.0f)) / 255.0f;  // stored in the frame first
  const glm::vec3 want = nearest.material.front * lit * a + wall * (1 - a);
  const uint8_t* centre = &image[(size_t(s.height / 2) * s.width + s.width / 2) * 4];
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(centre[c], want[c] * 255.0f, 1.0) << "channel " << c;
}

// Too few layers drop the farthest quads: no longer `sorted`.
TEST_F(PeelingTest, FewerLayersThanTheDepthComplexityAreNotTheComposite) {
  TranslucencySettings s = Settings("complexity");
  s.peelLayers = 4;
  EXPECT_GT(MaxChannelDifference(Render(s, Method("depth-peeling")), Render(s, Method("sorted"))), 8);
}

struct DualCase {
  const char* scene;
  uint32_t layers;
};
class DualTest : public PeelingTest, public ::testing::WithParamInterface<DualCase> {};

// Where the layers are all the layers (depth peeling's last one empty), both are the
// exact composite: the shards transmit coloured light, the quads plain.
TEST_P(DualTest, DualDepthPeelingEqualsDepthPeelingWithTheSameLayers) {
  TranslucencySettings s = Settings(GetParam().scene);
  s.peelLayers = GetParam().layers;
  const std::vector<uint64_t> layers = LayerSamples(s);
  ASSERT_FALSE(layers.empty());
  ASSERT_EQ(layers.back(), 0u) << "the scene has more than " << s.peelLayers << " layers";
  EXPECT_LE(MaxChannelDifference(Render(s, Method("dual-depth-peeling")), Render(s, Method("depth-peeling"))), 1);
}

INSTANTIATE_TEST_SUITE_P(Scenes, DualTest, ::testing::Values(DualCase{"complexity", 10}, DualCase{"shards", 16}));

// With 4 layers of 8 quads, dual depth peeling keeps the 2 nearest and the 2
// farthest, depth peeling the 4 nearest.
TEST_F(PeelingTest, WithTooFewLayersDualPeelingKeepsBothEnds) {
  TranslucencySettings s = Settings("complexity");
  s.peelLayers = 4;
  EXPECT_GT(MaxChannelDifference(Render(s, Method("dual-depth-peeling")), Render(s, Method("depth-peeling"))), 8);
}

// Layer k alone at the centre: the k-th nearest quad over grey 0.5, lit as meshes.fx
// lights it (ambient 0.45 plus Lambert); an empty layer is the grey alone.
TEST_F(PeelingTest, ALayerShownAloneIsTheKthNearestQuadOverGrey) {
  TranslucencySettings s = Settings("complexity");
  s.depthComplexity = 3;
  const renderer::QuadStack stack = renderer::ComplexityQuadStack(s);
  std::vector<renderer::TriangleMesh> quads = renderer::CameraFacingQuads(stack);
  const glm::vec3 forward = glm::normalize(stack.target - stack.eye);
  std::sort(quads.begin(), quads.end(), [&](const auto& a, const auto& b) {
    return glm::dot(a.positions[0] - stack.eye, forward) < glm::dot(b.positions[0] - stack.eye, forward);
  });
  const glm::vec3 light = renderer::SceneLightDirection();
  for (int k = 0; k <= 3; ++k) {
    s.showLayer = k;
    const std::vector<uint8_t> image = Render(s, Method("depth-peeling"));
    ASSERT_FALSE(image.empty());
    glm::vec3 want(0.5f);
    if (k < 3) {
      const renderer::TriangleMesh& q = quads[size_t(k)];
      const float lambert = std::max(0.0f, glm::dot(q.normals[0], light));
      want = q.material.front * (0.45f + 0.55f * lambert) * q.material.opacity + want * (1 - q.material.opacity);
    }
    const uint8_t* centre = &image[(size_t(s.height / 2) * s.width + s.width / 2) * 4];
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(centre[c], want[c] * 255.0f, 1.0) << "layer " << k << " channel " << c;
  }
}

TEST_F(PeelingTest, ShowingALayerTheMethodDoesNotKeepIsRefused) {
  for (const auto& [method, layer] : {std::pair{"depth-peeling", 8}, std::pair{"alpha", 0}}) {
    TranslucencySettings s = Settings("complexity");
    s.showLayer = layer;
    std::string error;
    auto t = Translucency::Create(device.Get(), context.Get(), s, &error);
    ASSERT_TRUE(t) << error;
    EXPECT_FALSE(t->RenderFrame(Method(method)));
    EXPECT_NE(t->error().find(std::string("keeps no layer ") + std::to_string(layer)), std::string::npos)
        << t->error();
  }
}

// The peeling passes a frame applies, from the call trace's effect-pass markers.
size_t PeelPasses(const std::vector<std::string>& markers) {
  return size_t(std::count_if(markers.begin(), markers.end(), [](const std::string& m) {
    return m == "SetMarker(DepthPeeling/PeelNearest)" || m == "SetMarker(DepthPeeling/Peel)";
  }));
}

// 3 quads, 8 layers: frame 0 knows nothing and peels 8; its layer 3 was empty, so
// frame 1 peels layers 0-3 (3 might have filled since) and draws the same image.
TEST_F(PeelingTest, AFrameAfterAnEmptyLayerPeelsUpToIt) {
  rhi::Trace trace;
  ComPtr<rhi::DeviceContext> traced;
  ASSERT_EQ(rhi::CreateTracingContext(context.Get(), &trace, traced.GetAddressOf()), rhi::S_OK);
  TranslucencySettings s = Settings("complexity");
  s.depthComplexity = 3;
  std::string error;
  auto t = Translucency::Create(device.Get(), traced.Get(), s, &error);
  ASSERT_TRUE(t) << error;
  const MethodInfo& peeling = Method("depth-peeling");
  ASSERT_TRUE(t->RenderFrame(peeling)) << t->error();
  EXPECT_EQ(PeelPasses(trace.Filter({"SetMarker"})), 8u);
  const std::vector<uint8_t> first = t->ReadFrame();
  EXPECT_EQ(t->MethodInstance(peeling)->LayerSamples(traced.Get())[3], 0u);
  trace.Clear();
  ASSERT_TRUE(t->RenderFrame(peeling)) << t->error();
  EXPECT_EQ(PeelPasses(trace.Filter({"SetMarker"})), 4u);
  EXPECT_TRUE(t->ReadFrame() == first);
  t.reset();
  traced.Reset();
}

}  // namespace
}  // namespace rhi_test
