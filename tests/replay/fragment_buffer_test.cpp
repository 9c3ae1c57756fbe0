// The fragment-buffer methods (document 004's prefix-sum buffer and per-pixel
// linked lists, renderer/src/oit/prefix_sum.cpp, linked_list.cpp) against
// computations that do not use them, validation layer on:
//  (the GPU prefix scan itself: tests/compute/prefix_scan_test.cpp)
//  - after a frame, each pixel's cursor equals its count, the offsets are the
//  CPU's
//    scan of the counts and the total their sum;
//  - deferred shading: every fragment's ShadeTriangle equals its forward Shade
//  within
//    1/255 (a recording method, data/fragment_record.fxh, evaluates both per
//    fragment);
//  - the images of both methods equal a composite computed on the CPU in double
//  from
//    the recorded fragments (sorted by depth, then triangle id), and each
//    other;
//  - the opaque pixels shaded from the visibility buffer equal the forward-shaded ones;
//  - depth peeling with enough layers equals prefix-sum on every scene;
//  - a pool too small for the frame reports exactly the fragments it lost;
//  - a scene of several objects is refused with the reason.
#include <algorithm>
#include <cmath>

#include "fx/effect.h"
#include "gpu_test.h"
#include "renderer/oit/prefix_sum.h"
#include "renderer/translucency.h"

namespace rhi_test {
namespace {

using renderer::Translucency;
using renderer::TranslucencySettings;
using renderer::oit::MethodInfo;

// ---------------------------------------------------------------------------
// A method that records every fragment with its forward and deferred shading.

// data/fragment_record.fxh's record.
struct FragmentRecord {
  uint32_t pixel, id;
  float depth;
  uint32_t unused;
  float forward[4], forwardTransmission[4];  // colour and alpha; transmission
  float deferred[4], deferredTransmission[4];
};
static_assert(sizeof(FragmentRecord) == 80);

constexpr uint32_t kMaxRecords = 1 << 20;

class RecordingMethod final : public renderer::oit::Method {
 public:
  RecordingMethod(rhi::Device* device, const renderer::oit::FrameDesc& frame) : frame_(frame) {
    const rhi::BUFFER_DESC desc{kMaxRecords * sizeof(FragmentRecord), rhi::USAGE_DEFAULT,
                                rhi::BIND_UNORDERED_ACCESS,           0,
                                rhi::RESOURCE_MISC_BUFFER_STRUCTURED, sizeof(FragmentRecord)};
    device->CreateBuffer(&desc, nullptr, records_.GetAddressOf());
    rhi::UNORDERED_ACCESS_VIEW_DESC u{};
    u.Format = rhi::DXGI_FORMAT_UNKNOWN;
    u.ViewDimension = rhi::UAV_DIMENSION_BUFFER;
    u.Buffer = {0, kMaxRecords, rhi::BUFFER_UAV_FLAG_APPEND};
    device->CreateUnorderedAccessView(records_.Get(), &u, uav_.GetAddressOf());
  }
  void Render(const renderer::oit::RenderArgs& a) override {
    a.marks->BeginPass(0);
    rhi::UnorderedAccessView* uav = uav_.Get();
    const UINT zero = 0;
    a.context->OMSetRenderTargetsAndUnorderedAccessViews(0, nullptr, a.targets.depth, 0, 1, &uav, &zero);
    a.geometry->SetEffectVariables([&](fx::Effect& e) {
      e.GetVariableByName("Records")->AsUnorderedAccessView()->SetUnorderedAccessView(uav_.Get());
      e.GetVariableByName("RecordWidth")->AsScalar()->SetInt(int(frame_.width));
      const float size[4] = {float(frame_.width), float(frame_.height), 0, 0};
      e.GetVariableByName("FrameSize")->AsVector()->SetFloatVector(size);
    });
    a.geometry->Draw(a.context, "Record", renderer::oit::DrawOrder::AsSubmitted);
    a.context->OMSetRenderTargets(0, nullptr, nullptr);
  }
  uint64_t MemoryBytes() const override { return 0; }
  const std::vector<std::string>& PassNames() const override { return passes_; }

  rhi::Buffer* records() const { return records_.Get(); }
  rhi::UnorderedAccessView* uav() const { return uav_.Get(); }

 private:
  renderer::oit::FrameDesc frame_;
  ComPtr<rhi::Buffer> records_;
  ComPtr<rhi::UnorderedAccessView> uav_;
  std::vector<std::string> passes_{"Record"};
};

std::unique_ptr<renderer::oit::Method> CreateRecording(const MethodInfo&, const renderer::oit::MethodSetup& setup,
                                                       std::string*) {
  return std::make_unique<RecordingMethod>(setup.device, setup.frame);
}
const MethodInfo kRecord{"record",
                         PROJECT_SOURCE_ROOT "/tests/replay/data/fragment_record.fxh",
                         renderer::oit::kNeedsPixelShaderUavs,
                         renderer::oit::DrawOrder::AsSubmitted,
                         "test: records fragments",
                         CreateRecording};

struct SceneCase {
  const char* scene;
  int frames;  // the frame recorded and compared is the last
  // Of ShadeTriangle against Shade: 1/255; the billboards 2/255, where the
  // puff's density is steepest and the rasterizer's interpolated uv differs from
  // the exact point where the pixel's ray meets the billboard (at worst 1.4/255 on
  // lavapipe, 1.9/255 on an NVIDIA H100).
  float shadeTolerance;
};

class FragmentBufferTest : public GpuTest, public ::testing::WithParamInterface<SceneCase> {
 protected:
  static TranslucencySettings Settings(const char* scene) {
    TranslucencySettings s;
    s.scene = scene;
    s.width = 64, s.height = 36;
    s.rule = {24, 2, 15, 20};
    s.shardCount = 300;
    s.fragmentStorage.nodesPerPixel = 64;
    return s;
  }
  std::unique_ptr<Translucency> Make(const TranslucencySettings& s) {
    std::string error;
    auto t = Translucency::Create(device.Get(), context.Get(), s, &error);
    EXPECT_NE(t, nullptr) << error;
    return t;
  }
  // The scene's frames up to the last with `method`, and the last with `last`.
  std::vector<uint8_t> Render(Translucency& t, const MethodInfo& last, int frames) {
    for (int i = 0; i + 1 < frames; ++i) EXPECT_TRUE(t.RenderFrame(*renderer::oit::FindMethod("alpha"))) << t.error();
    EXPECT_TRUE(t.RenderFrame(last)) << t.error();
    return t.ReadFrame();
  }
  std::vector<FragmentRecord> Records(Translucency& t) {
    auto* method = const_cast<RecordingMethod*>(dynamic_cast<const RecordingMethod*>(t.MethodInstance(kRecord)));
    const uint32_t sentinel = 0;
    ComPtr<rhi::Buffer> count = MakeBuffer(0, &sentinel, 4);
    context->CopyStructureCount(count.Get(), 0, method->uav());
    const uint32_t n = ReadBufferAs<uint32_t>(count.Get())[0];
    EXPECT_LT(n, kMaxRecords);
    std::vector<FragmentRecord> all = ReadBufferAs<FragmentRecord>(method->records());
    all.resize(std::min<size_t>(n, all.size()));
    return all;
  }
};

TEST_P(FragmentBufferTest, DeferredShadingEqualsForwardShadingForEveryFragment) {
  auto t = Make(Settings(GetParam().scene));
  ASSERT_TRUE(t);
  Render(*t, kRecord, GetParam().frames);
  const std::vector<FragmentRecord> records = Records(*t);
  ASSERT_GT(records.size(), 200u);
  float worst = 0;
  for (const FragmentRecord& r : records)
    for (int c = 0; c < 4; ++c)
      worst = std::max({worst, std::abs(r.forward[c] - r.deferred[c]),
                        std::abs(r.forwardTransmission[c] - r.deferredTransmission[c])});
  std::printf("%s: %zu fragments, largest |deferred - forward| %.6f\n", GetParam().scene, records.size(), worst);
  EXPECT_LE(worst, GetParam().shadeTolerance);
}

// Front to back in double: C += T a saturate(c), T *= 1 - a (1 - t) for coloured
// transmission (shards), 1 - a otherwise; frame = C + T * opaque; stored as
// RGBA8 rounds. (saturate: the exact methods' SurfaceColour, oit/common.fxh.)
std::vector<uint8_t> CpuComposite(std::vector<FragmentRecord> records, const std::vector<uint8_t>& opaque,
                                  bool coloredTransmission) {
  std::sort(records.begin(), records.end(), [](const FragmentRecord& a, const FragmentRecord& b) {
    if (a.pixel != b.pixel) return a.pixel < b.pixel;
    return a.depth != b.depth ? a.depth < b.depth : a.id < b.id;
  });
  std::vector<uint8_t> image = opaque;
  for (size_t i = 0; i < records.size();) {
    const uint32_t pixel = records[i].pixel;
    double C[3] = {0, 0, 0}, T[3] = {1, 1, 1};
    for (; i < records.size() && records[i].pixel == pixel; ++i) {
      const FragmentRecord& r = records[i];
      for (int c = 0; c < 3; ++c) {
        const double a = r.deferred[3];
        C[c] += T[c] * a * std::clamp(double(r.deferred[c]), 0.0, 1.0);
        T[c] *= coloredTransmission ? 1.0 - a * (1.0 - r.deferredTransmission[c]) : 1.0 - a;
      }
    }
    for (int c = 0; c < 3; ++c) {
      const double v = C[c] + T[c] * opaque[pixel * 4 + c] / 255.0;
      image[pixel * 4 + c] = uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
    }
  }
  return image;
}

int LargestDifference(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  int worst = 0;
  for (size_t i = 0; i < a.size(); ++i)
    if (i % 4 != 3) worst = std::max(worst, std::abs(int(a[i]) - int(b[i])));
  return worst;
}

// On lavapipe (Mesa 22, llvmpipe) the linked lists come out wrong along triangle
// edges: pixels there lose their whole list or walk into other pixels' nodes (the
// resolve then runs into llvmpipe's 65535-turn loop cap), while the node counter is
// exact (the test below) and prefix-sum, whose atomics add per pixel, equals the CPU
// reference. The head update is what breaks: with InterlockedMax instead of
// InterlockedExchange (valid only where nodes are taken in the order a pixel's
// fragments update its head, as on llvmpipe) the complexity image equals prefix-sum's.
// A compare-exchange loop breaks alike; not the depth test, the counter kind, a bound
// render target, an SV_Coverage guard against helpers, 16-byte nodes or llvmpipe's
// vector width. These checks skip there (README, Known gaps).
bool LinkedListsBrokenHere(rhi::Device* device) {
  return std::string(device->GetAdapterName()).find("llvmpipe") == 0;
}

TEST_P(FragmentBufferTest, PrefixSumEqualsTheCpuCompositeOfTheSameFragments) {
  const TranslucencySettings s = Settings(GetParam().scene);
  auto recording = Make(s);
  ASSERT_TRUE(recording);
  const std::vector<uint8_t> opaque = Render(*recording, kRecord, GetParam().frames);
  const std::vector<uint8_t> want =
      CpuComposite(Records(*recording), opaque, std::string(GetParam().scene) == "shards");
  EXPECT_GT(LargestDifference(want, opaque), 30) << "the translucent object shows";
  const MethodInfo& prefixSum = *renderer::oit::FindMethod("prefix-sum");
  auto t = Make(s);
  ASSERT_TRUE(t);
  const std::vector<uint8_t> got = Render(*t, prefixSum, GetParam().frames);
  EXPECT_LE(LargestDifference(got, want), 1);

  EXPECT_EQ(t->MethodInstance(prefixSum)->LostFragments(), 0u);
}

TEST_P(FragmentBufferTest, LinkedListEqualsPrefixSum) {
  if (LinkedListsBrokenHere(device.Get())) GTEST_SKIP() << "lavapipe breaks the linked lists along triangle edges";
  const TranslucencySettings s = Settings(GetParam().scene);
  std::vector<std::vector<uint8_t>> images;
  for (const char* name : {"prefix-sum", "linked-list"}) {
    auto t = Make(s);
    ASSERT_TRUE(t);
    images.push_back(Render(*t, *renderer::oit::FindMethod(name), GetParam().frames));
  }
  EXPECT_LE(LargestDifference(images[0], images[1]), 1);
}

// Document 004's opaque pixels come from the visibility buffer: where no translucent
// fragment lies (count 0), prefix-sum's frame is the opaque backdrop shaded from its
// triangle ids, which must equal the forward-shaded backdrop (the recording method's
// frame: scene.fx Opaque/Scene) within one 8-bit step. The backdrop must show.
TEST_P(FragmentBufferTest, TheVisibilityBufferShadesTheOpaquePixelsAsForwardShadingDoes) {
  const TranslucencySettings s = Settings(GetParam().scene);
  auto recording = Make(s);
  ASSERT_TRUE(recording);
  const std::vector<uint8_t> forward = Render(*recording, kRecord, GetParam().frames);
  const MethodInfo& prefixSum = *renderer::oit::FindMethod("prefix-sum");
  auto t = Make(s);
  ASSERT_TRUE(t);
  const std::vector<uint8_t> deferred = Render(*t, prefixSum, GetParam().frames);
  const auto frame = renderer::oit::ReadPrefixSumFrame(*t->MethodInstance(prefixSum), context.Get());
  ASSERT_TRUE(frame);
  int worst = 0;
  size_t opaquePixels = 0, backdrop = 0;
  for (size_t pixel = 0; pixel < frame->counts.size(); ++pixel) {
    if (frame->counts[pixel] != 0) continue;
    ++opaquePixels;
    bool sky = true;
    for (int c = 0; c < 3; ++c) {
      worst = std::max(worst, std::abs(int(forward[pixel * 4 + c]) - int(deferred[pixel * 4 + c])));
      sky = sky && std::abs(forward[pixel * 4 + c] - renderer::kSkyColour[c] * 255.0f) <= 0.5f;
    }
    backdrop += !sky;
  }
  EXPECT_GT(opaquePixels, frame->counts.size() / 10);
  EXPECT_GT(backdrop, opaquePixels / 4) << "the backdrop shows";
  EXPECT_LE(worst, 1);
}

// Exact means exact: depth peeling with as many layers as the deepest pixel has
// fragments (prefix-sum's counts say how many) composites the same image as
// prefix-sum, within one 8-bit step where both shade alike (ShadeTriangle against
// Shade: 1/255) and two on the billboards, whose deferred shading differs from the
// rasterizer's interpolation by up to shadeTolerance (2/255: the test above).
// Except where two fragments of a pixel lie at the same depth: a peel keeps what lies
// strictly behind the last layer, so depth peeling keeps one of them (document 002's
// method cannot part coplanar surfaces; the smoke's newborn particles share their
// emitter's centre). Those pixels are found from the recorded fragments and left out.
TEST_P(FragmentBufferTest, DepthPeelingWithEnoughLayersEqualsPrefixSum) {
  TranslucencySettings s = Settings(GetParam().scene);
  const MethodInfo& prefixSum = *renderer::oit::FindMethod("prefix-sum");
  auto exact = Make(s);
  ASSERT_TRUE(exact);
  const std::vector<uint8_t> want = Render(*exact, prefixSum, GetParam().frames);
  const auto frame = renderer::oit::ReadPrefixSumFrame(*exact->MethodInstance(prefixSum), context.Get());
  ASSERT_TRUE(frame);
  s.peelLayers = *std::max_element(frame->counts.begin(), frame->counts.end());
  ASSERT_GT(s.peelLayers, 1u);
  auto peeled = Make(s);
  ASSERT_TRUE(peeled);
  const std::vector<uint8_t> got = Render(*peeled, *renderer::oit::FindMethod("depth-peeling"), GetParam().frames);
  auto recording = Make(s);
  ASSERT_TRUE(recording);
  Render(*recording, kRecord, GetParam().frames);
  std::vector<FragmentRecord> records = Records(*recording);
  std::sort(records.begin(), records.end(), [](const FragmentRecord& a, const FragmentRecord& b) {
    return a.pixel != b.pixel ? a.pixel < b.pixel : a.depth < b.depth;
  });
  std::vector<bool> tied(frame->counts.size());
  for (size_t i = 1; i < records.size(); ++i)
    if (records[i].pixel == records[i - 1].pixel && records[i].depth == records[i - 1].depth &&
        records[i].deferred[3] > 0 && records[i - 1].deferred[3] > 0)  // a = 0 takes no layer
      tied[records[i].pixel] = true;
  const int tolerance = GetParam().shadeTolerance > 1 / 255.0f ? 2 : 1;
  int worst = 0;
  size_t compared = 0, worstPixel = 0;
  for (size_t pixel = 0; pixel < tied.size(); ++pixel) {
    if (tied[pixel]) continue;
    compared += frame->counts[pixel] > 1;
    for (int c = 0; c < 3; ++c)
      if (const int d = std::abs(int(got[pixel * 4 + c]) - int(want[pixel * 4 + c])); d > worst)
        worst = d, worstPixel = pixel;
  }
  EXPECT_GT(compared, 20u) << "pixels of several fragments";
  EXPECT_LE(worst, tolerance) << s.peelLayers << " layers; " << std::count(tied.begin(), tied.end(), true)
                              << " pixels with a depth tie left out; the worst at (" << worstPixel % s.width << ", "
                              << worstPixel / s.width << "), " << frame->counts[worstPixel] << " fragments";
}

INSTANTIATE_TEST_SUITE_P(Scenes, FragmentBufferTest,
                         ::testing::Values(SceneCase{"shards", 1, 1 / 255.0f}, SceneCase{"smoke", 20, 2 / 255.0f},
                                           SceneCase{"fire", 20, 2 / 255.0f}, SceneCase{"complexity", 1, 1 / 255.0f},
                                           SceneCase{"teapot", 1, 1 / 255.0f}, SceneCase{"cubes", 1, 1 / 255.0f},
                                           SceneCase{"ice-in-cup", 1, 1 / 255.0f},
                                           SceneCase{"magic-circle", 1, 1 / 255.0f}),
                         [](const ::testing::TestParamInfo<SceneCase>& info) {
                           std::string name = info.param.scene;  // gtest names: no '-'
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

// ---------------------------------------------------------------------------

class FragmentStorageTest : public FragmentBufferTest {};

// Document 004's step 4: the cursors end equal to the counts; step 3: the
// offsets are the exclusive scan of the counts and the total their sum.
TEST_F(FragmentStorageTest, CursorsEndEqualToCountsAndOffsetsScanThem) {
  for (const char* scene : {"shards", "teapot"}) {
    auto t = Make(Settings(scene));
    ASSERT_TRUE(t);
    Render(*t, *renderer::oit::FindMethod("prefix-sum"), 1);
    const auto frame =
        renderer::oit::ReadPrefixSumFrame(*t->MethodInstance(*renderer::oit::FindMethod("prefix-sum")), context.Get());
    ASSERT_TRUE(frame);
    EXPECT_EQ(frame->cursors, frame->counts) << scene;
    uint32_t sum = 0;
    for (size_t i = 0; i < frame->counts.size(); ++i) {
      ASSERT_EQ(frame->offsets[i], sum) << scene << " pixel " << i;
      sum += frame->counts[i];
    }
    EXPECT_EQ(frame->total, sum) << scene;
    EXPECT_GT(*std::max_element(frame->counts.begin(), frame->counts.end()), 3u) << scene << ": layers overlap";
  }
}

// The smallest pool, one node a pixel, on 3000 shards, which need more: the
// method reports exactly how many fragments it could not store (the recorded
// count of the frame's fragments minus the pool), a frame or two late.
// The hysteresis sizing that redraws: the smoke grows past 1.5x its first frame's
// fragments, so some frames do not fit the buffer their fill had and are drawn again;
// every frame then equals the exactly sized one, bit for bit, and nothing is lost.
TEST_F(FragmentStorageTest, GrowAndRedrawDrawsAgainWhatDidNotFitAndEqualsExactSizing) {
  const MethodInfo& prefixSum = *renderer::oit::FindMethod("prefix-sum");
  TranslucencySettings exact = Settings("smoke"), redraw = exact;
  redraw.fragmentStorage.sizing = renderer::oit::FragmentSizing::GrowAndRedraw;
  auto a = Make(exact), b = Make(redraw);
  ASSERT_TRUE(a && b);
  for (int frame = 0; frame < 20; ++frame) {
    ASSERT_TRUE(a->RenderFrame(prefixSum)) << a->error();
    ASSERT_TRUE(b->RenderFrame(prefixSum)) << b->error();
    ASSERT_EQ(a->ReadFrame(), b->ReadFrame()) << "frame " << frame;
    EXPECT_EQ(b->MethodInstance(prefixSum)->LostFragments(), 0u) << "frame " << frame;
  }
  EXPECT_GT(b->redrawnFrames(), 0u);
  EXPECT_LT(b->redrawnFrames(), 10u) << "the hysteresis keeps most frames from redrawing";
  EXPECT_EQ(a->redrawnFrames(), 0u);
}

TEST_F(FragmentStorageTest, ALinkedListPoolTooSmallReportsTheFragmentsItLost) {
  TranslucencySettings s = Settings("shards");
  s.shardCount = 3000;
  auto recording = Make(s);
  ASSERT_TRUE(recording);
  Render(*recording, kRecord, 1);
  const size_t fragments = Records(*recording).size();
  s.fragmentStorage.nodesPerPixel = 1;
  auto t = Make(s);
  ASSERT_TRUE(t);
  const MethodInfo& linked = *renderer::oit::FindMethod("linked-list");
  // Frame 0 (as recorded), read back at the start of frame 1: the camera swings, so
  // later frames have other counts.
  ASSERT_TRUE(t->RenderFrame(linked)) << t->error();
  t->ReadFrame();  // the GPU has finished frame 0: frame 1 reads its count without waiting
  ASSERT_TRUE(t->RenderFrame(linked)) << t->error();
  const uint64_t pool = uint64_t(s.width) * s.height;
  ASSERT_GT(fragments, pool);
  EXPECT_EQ(t->MethodInstance(linked)->LostFragments(), fragments - pool);
}

TEST_F(FragmentStorageTest, AllFitsWhenThePoolIsLargeEnough) {
  auto t = Make(Settings("shards"));
  ASSERT_TRUE(t);
  const MethodInfo& linked = *renderer::oit::FindMethod("linked-list");
  for (int frame = 0; frame < 3; ++frame) {
    ASSERT_TRUE(t->RenderFrame(linked)) << t->error();
    t->ReadFrame();
  }
  EXPECT_EQ(t->MethodInstance(linked)->LostFragments(), 0u);
}

TEST_F(FragmentStorageTest, ScenesOfSeveralObjectsAreRefusedWithTheReason) {
  for (const char* name : {"prefix-sum", "linked-list"}) {
    TranslucencySettings s = Settings("smoke");
    s.extraShards = 10;
    auto t = Make(s);
    ASSERT_TRUE(t);
    EXPECT_FALSE(t->RenderFrame(*renderer::oit::FindMethod(name)));
    EXPECT_NE(t->error().find("one translucent object"), std::string::npos) << t->error();
    EXPECT_NE(t->error().find("has 2"), std::string::npos) << t->error();
  }
}

}  // namespace
}  // namespace rhi_test
