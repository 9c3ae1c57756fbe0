// Golden images of document 000's demos at 96x54: every demo (smoke, fire,
// shards) with every method (alpha, wboit, colored, sorted), compared with a
// tolerance against tests/replay/golden/<demo>_<method>.png.
//
// The goldens were rendered on lavapipe (Mesa llvmpipe) by this test with
// REPLAY_WRITE_GOLDEN=tests/replay/golden, then checked before being committed:
//  - by eye (each PNG viewed: the opaque stripes, floor and cubes; smoke puffs lit
//    from the upper left / flames / tinted shards; OVER showing the newest smoke on top,
//    WBOIT blending the layers, colored OIT tinting the wall behind the shards);
//  - against the sorted reference: RMSE to <demo>_sorted.png below the bounds in
//    kSortedBound (the numbers measured when they were made are in the comments),
//    which this test keeps asserting on the fresh renders.
// Tolerance against the golden: RMSE <= 1.5 (8-bit steps) and at most 1% of the
// pixels off by more than 8 in a channel: rasterization and filtering may differ
// slightly between Vulkan implementations; a wrong blend state, weight, pass or
// draw changes far more.
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "gpu_test.h"
#include "renderer/translucency.h"

namespace rhi_test {
namespace {

using renderer::Translucency;
using renderer::TranslucencyDemo;
using renderer::TranslucencyMethod;
using renderer::TranslucencySettings;

constexpr uint32_t kWidth = 96, kHeight = 54;

TranslucencySettings GoldenSettings(TranslucencyDemo demo) {
  TranslucencySettings s;
  s.demo = demo;
  s.width = kWidth, s.height = kHeight;
  s.rule = {24, 2, 15, 20};  // ~1k particles, steady after 35 updates
  s.shardCount = 600;
  return s;
}
int GoldenFrames(TranslucencyDemo demo) { return demo == TranslucencyDemo::Shards ? 1 : 40; }

// Upper bounds of the RMSE to the sorted reference (8-bit steps), a little above what
// lavapipe measured when the goldens were made.
double SortedBound(TranslucencyDemo demo, TranslucencyMethod method) {
  if (method == TranslucencyMethod::Sorted) return 0.0;
  switch (demo) {
    case TranslucencyDemo::Smoke:  // measured: alpha 8.333 (newest on top), wboit 3.809, colored 8.718
      return method == TranslucencyMethod::Alpha ? 9.5 : method == TranslucencyMethod::Wboit ? 4.5 : 10.0;
    case TranslucencyDemo::Fire:  // additive is order-independent: alpha == sorted exactly (measured 0.000);
                                  // wboit 15.273, colored 13.273 (the OIT tables average instead of adding)
      return method == TranslucencyMethod::Alpha ? 0.0 : method == TranslucencyMethod::Wboit ? 17.0 : 15.0;
    case TranslucencyDemo::Shards:  // measured: alpha 5.832, wboit 4.494, colored 22.547 (the tint of the
                                    // transmitted background, which OVER and so the reference lack)
      return method == TranslucencyMethod::Alpha ? 6.5 : method == TranslucencyMethod::Wboit ? 5.5 : 25.0;
  }
  return 0;
}

class GoldenTest : public GpuTest {
 protected:
  std::vector<uint8_t> Render(TranslucencyDemo demo, TranslucencyMethod method) {
    std::string error;
    auto t = Translucency::Create(device.Get(), context.Get(), GoldenSettings(demo), &error);
    EXPECT_NE(t, nullptr) << error;
    if (!t) return {};
    for (int i = 0; i < GoldenFrames(demo); ++i) t->RenderFrame(method);
    return t->ReadFrame();
  }
};

std::string Name(TranslucencyDemo demo, TranslucencyMethod method) {
  return std::string(renderer::ToString(demo)) + "_" + renderer::ToString(method);
}

std::vector<uint8_t> LoadPng(const std::string& path) {
  int w = 0, h = 0, n = 0;
  stbi_uc* data = stbi_load(path.c_str(), &w, &h, &n, 4);
  if (!data) return {};
  std::vector<uint8_t> out;
  if (uint32_t(w) == kWidth && uint32_t(h) == kHeight) out.assign(data, data + size_t(w) * h * 4);
  stbi_image_free(data);
  return out;
}

TEST_F(GoldenTest, EveryDemoAndMethodMatchesItsGoldenImage) {
  const char* write = std::getenv("REPLAY_WRITE_GOLDEN");
  const std::string dir = PROJECT_SOURCE_ROOT "/tests/replay/golden";
  for (TranslucencyDemo demo : {TranslucencyDemo::Smoke, TranslucencyDemo::Fire, TranslucencyDemo::Shards}) {
    const std::vector<uint8_t> sorted = Render(demo, TranslucencyMethod::Sorted);
    for (TranslucencyMethod method : {TranslucencyMethod::Alpha, TranslucencyMethod::Wboit,
                                      TranslucencyMethod::Colored, TranslucencyMethod::Sorted}) {
      const std::string name = Name(demo, method);
      SCOPED_TRACE(name);
      const std::vector<uint8_t> image = method == TranslucencyMethod::Sorted ? sorted : Render(demo, method);
      ASSERT_EQ(image.size(), size_t(kWidth) * kHeight * 4);
      const double toSorted = renderer::Rmse(image, sorted);
      std::printf("%-16s RMSE to sorted %.3f\n", name.c_str(), toSorted);
      EXPECT_LE(toSorted, SortedBound(demo, method) + 1e-9);
      if (write && *write) {
        std::filesystem::create_directories(write);
        const std::string path = std::string(write) + "/" + name + ".png";
        ASSERT_TRUE(stbi_write_png(path.c_str(), kWidth, kHeight, 4, image.data(), kWidth * 4)) << path;
        continue;
      }
      const std::vector<uint8_t> golden = LoadPng(dir + "/" + name + ".png");
      ASSERT_FALSE(golden.empty()) << dir << "/" << name << ".png missing or not " << kWidth << "x" << kHeight;
      const double rmse = renderer::Rmse(image, golden);
      size_t off = 0;
      for (size_t i = 0; i < image.size(); i += 4)
        for (int c = 0; c < 3; ++c)
          if (std::abs(int(image[i + c]) - int(golden[i + c])) > 8) {
            ++off;
            break;
          }
      EXPECT_LE(rmse, 1.5) << "RMSE to the golden image";
      EXPECT_LE(off, size_t(kWidth) * kHeight / 100) << "pixels off by more than 8";
    }
  }
}

}  // namespace
}  // namespace rhi_test
