// The compute-tile methods (issue 19: renderer/src/oit/compute_tiles.cpp,
// shaders_hlsl/oit/compute_tiles.fxh) against the ROP methods they replay, on the
// same frame (RenderFrameAgain), validation layer with synchronization validation on:
//  - compute-sorted equals `sorted` within 1/255 a channel: the same particles in the
//    same order (a GPU radix sort against std::stable_sort), the same shading, each
//    blend rounded as the output merger rounds into the frame;
//  - compute-wboit equals `wboit` within the rounding its RGBA16F / R8 targets explain;
//  - pair buffers too small for a frame grow and the frame is drawn again, complete;
//  - a scene of other primitives is refused with the reason.
// The references are independent of the code under test: `sorted` sorts on the CPU
// and blends with the output merger; `wboit` blends with the output merger.
#include <algorithm>
#include <cstdlib>

#include "gpu_test.h"
#include "method_lookup.h"
#include "renderer/translucency.h"

namespace rhi_test {
namespace {

using renderer::Translucency;
using renderer::TranslucencySettings;

// The largest difference of the two images in any colour channel, and how many
// pixels differ at all.
struct ImageDifference {
  int largest = 0;
  size_t pixels = 0;
};
ImageDifference Compare(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  ImageDifference d;
  for (size_t i = 0; i + 3 < a.size() && i + 3 < b.size(); i += 4) {
    int largest = 0;
    for (size_t c = 0; c < 3; ++c) largest = std::max(largest, std::abs(int(a[i + c]) - int(b[i + c])));
    d.largest = std::max(d.largest, largest);
    d.pixels += largest > 0;
  }
  return d;
}

class ComputeTilesTest : public GpuTest, public ::testing::WithParamInterface<const char*> {
 protected:
  // The particle scenes at a small size, 40 updates: the smoke's steady state.
  static TranslucencySettings Settings(const char* scene) {
    TranslucencySettings s;
    s.scene = scene;
    s.width = 200, s.height = 120;
    s.countParticles = true;  // `sorted` draws the frame again
    return s;
  }
  std::unique_ptr<Translucency> Replay(const TranslucencySettings& s, const char* method, int frames) {
    std::string error;
    auto t = Translucency::Create(device.Get(), context.Get(), s, &error);
    EXPECT_NE(t, nullptr) << error;
    if (!t) return nullptr;
    for (int i = 0; i < frames; ++i) EXPECT_TRUE(t->RenderFrame(Method(method))) << t->error();
    return t;
  }
  // The last frame again with `method`.
  static std::vector<uint8_t> Again(Translucency& t, const char* method) {
    EXPECT_TRUE(t.RenderFrameAgain(Method(method))) << t.error();
    return t.ReadFrame();
  }
};

TEST_P(ComputeTilesTest, ComputeSortedEqualsSortedWithinOneStep) {
  auto t = Replay(Settings(GetParam()), "compute-sorted", 40);
  ASSERT_TRUE(t);
  const std::vector<uint8_t> compute = t->ReadFrame(), sorted = Again(*t, "sorted");
  const ImageDifference d = Compare(compute, sorted);
  std::printf("%s: compute-sorted vs sorted: largest %d/255, %zu pixels differ\n", GetParam(), d.largest, d.pixels);
  EXPECT_LE(d.largest, 1);
  EXPECT_TRUE(Refusals().empty());
}

// The ROP's sums are rounded as their targets store them, in the order the ROP
// blends (buffer order); compute-wboit rounds the same sums the same way in the same
// order, so what remains is how each rounds a float to half and to 8 bits.
TEST_P(ComputeTilesTest, ComputeWboitEqualsWboitWithinItsTargetsRounding) {
  auto t = Replay(Settings(GetParam()), "compute-wboit", 40);
  ASSERT_TRUE(t);
  const std::vector<uint8_t> compute = t->ReadFrame(), rop = Again(*t, "wboit");
  const ImageDifference d = Compare(compute, rop);
  std::printf("%s: compute-wboit vs wboit: largest %d/255, %zu pixels differ\n", GetParam(), d.largest, d.pixels);
  EXPECT_LE(d.largest, 2);
}

INSTANTIATE_TEST_SUITE_P(ParticleScenes, ComputeTilesTest, ::testing::Values("smoke", "fire"));

// Particles 8x as large touch ~64x the tiles: more pairs than the buffers first
// hold. The frame that overflows is drawn again with them grown, and is complete.
TEST_F(ComputeTilesTest, PairBuffersTooSmallGrowAndTheFrameIsDrawnAgain) {
  TranslucencySettings s = Settings("smoke");
  s.particleSize = 2.4f;
  s.width = 320, s.height = 200;
  auto t = Replay(s, "compute-sorted", 30);
  ASSERT_TRUE(t);
  EXPECT_GE(t->redrawnFrames(), 1u);
  const std::vector<uint8_t> compute = t->ReadFrame(), sorted = Again(*t, "sorted");
  EXPECT_LE(Compare(compute, sorted).largest, 1);
}

TEST_F(ComputeTilesTest, ScenesOfOtherPrimitivesAreRefusedWithTheReason) {
  for (const char* method : {"compute-sorted", "compute-wboit"}) {
    std::string error;
    auto t = Translucency::Create(device.Get(), context.Get(), Settings("shards"), &error);
    ASSERT_NE(t, nullptr) << error;
    std::string why;
    EXPECT_FALSE(t->Accepts(Method(method), &why));
    EXPECT_FALSE(t->RenderFrame(Method(method)));
    EXPECT_NE(t->error().find("particles"), std::string::npos) << t->error();
    EXPECT_EQ(t->error(), why);
  }
}

}  // namespace
}  // namespace rhi_test
