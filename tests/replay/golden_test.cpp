// Golden images of the replays at 96x54: every registered scene with every
// registered method, compared with a tolerance against
// tests/replay/golden/<scene>_<method>.png.
//
// The goldens were rendered on lavapipe (Mesa llvmpipe) by this test with
// REPLAY_WRITE_GOLDEN=tests/replay/golden, then checked before being committed
// (the colored-literal ones when Table 4 as printed became a method of its own;
// the others are unchanged since document 000's replay and still pass):
//  - by eye (each PNG viewed: the opaque stripes, floor and cubes; smoke puffs lit
//    from the upper left / flames / tinted shards; OVER showing the newest smoke on top,
//    WBOIT blending the layers, colored OIT tinting the wall behind the shards);
//  - against the sorted reference: RMSE to <scene>_sorted.png below the bounds in
//    kSortedBounds (the numbers measured when they were made are in the comments),
//    which this test keeps asserting on the fresh renders;
//  - colored-literal: darker than colored wherever the layers are dense, as Table 4
//    as printed predicts (it adds C * revealage, ~0 there, over the frame Table 3
//    darkened); tests/conformance/oit_tables_test.cpp checks that table pixel by
//    pixel against the CPU model of the D3D11 blend rules.
// The teapot and complexity goldens (documents 002 and 004) were checked the same
// way (viewed at 3x: the teapot red outside with its green inside showing through,
// unsorted alpha drawing the bottom's inside over the body, WBOIT paler; the quads'
// colours mixing over the grey wall), and their fresh renders, at these settings,
// against computations that do not use the goldens (exact_scenes_test.cpp):
// complexity/sorted's centre equals OVER of the 8 quads composited on the CPU, and
// teapot/sorted's near wall is red, its inside seen from within green, its ground blue.
// The depth-peeling and dual-depth-peeling goldens (document 002, 8 layers) were
// viewed at 3x beside sorted (the teapot and the quads as sorted shows them; the
// smoke thinner and the fire faint, their farther layers missing; the shards tinting
// the wall through their colours) and checked against computations that do not use
// them (peeling_test.cpp): on the complexity scene depth peeling is within one step
// of sorted everywhere, which exact_scenes_test.cpp checks against the CPU; dual
// peeling is within one step of depth peeling there and on 40 shards; at these
// settings, with 64 layers, the shards have 12 layers, and the teapot's and the
// complexity stack's images of both methods are within one step of each other.
// The prefix-sum goldens (document 004) were viewed at 3x beside sorted (smoke and
// teapot alike, fire darker and orange as OVER instead of additive, shards tinted by
// their coloured transmission as colored OIT's are) and their fresh renders are, at
// 64x36, within 1/255 per channel of a composite computed on the CPU in double from
// the same fragments and their deferred shading (fragment_buffer_test.cpp).
// The three exact methods' goldens were made again when the peeling methods came to
// composite in float32 (float_composite.hlsli) and every exact method to saturate a
// surface's colour (common.fxh SurfaceColour): viewed at 3x beside the old ones and
// sorted (the same pictures; the shards' specular no longer brighter in prefix-sum),
// depth peeling with enough layers equals prefix-sum within a step on every scene
// (fragment_buffer_test.cpp), and prefix-sum the CPU composite.
// Document 003's goldens (mboit, moment-transparency, -mindepth and -mindepth-r16 on
// every scene; every method on cubes, ice-in-cup and magic-circle) were viewed at 2x
// beside sorted and prefix-sum (the cubes' colours mixing through the blue one, the ice
// brighter than exact under plain Moment Transparency and closer to it with the
// correction, the decal paler without it; the R16 nearest depth breaking the nearest
// surface's weight: the teapot green, the decal faint, as the thesis found) and checked
// against computations that do not use them: moments_test.cpp (conformance) evaluates
// the reconstruction against its closed-form bound, document003_test.cpp measures the
// methods against the exact prefix-sum. `sorted` orders whole triangles, so on the
// magic circle (a big floor quad under the decal) it is no reference: the corrected
// method is farther from it and nearer the exact result.
// The wboit-msaa goldens and the triangles scene's (document 001) were viewed at 3x beside
// sorted and wboit (the same colours inside the surfaces, checked pixel by pixel on the
// teapot and the triangles; antialiased edges; the additive variants brighter, the
// linear one least washed out, the exposure one darker than additive) and their fresh
// renders are checked, at 64x36, against CPU models computed from the method's own
// multisampled targets read back sample by sample (wboit_msaa_test.cpp): the per-sample
// composite, the per-pixel one and the variants within one 8-bit step.
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
using renderer::TranslucencySettings;
using renderer::oit::MethodInfo;

constexpr uint32_t kWidth = 96, kHeight = 54;

TranslucencySettings GoldenSettings(const renderer::SceneInfo& scene) {
  TranslucencySettings s;
  s.scene = scene.name;
  s.width = kWidth, s.height = kHeight;
  s.rule = {24, 2, 15, 20};  // ~1k particles, steady after 35 updates
  s.shardCount = 600;
  return s;
}
int GoldenFrames(const renderer::SceneInfo& scene) { return scene.defaultFrames > 1 ? 40 : 1; }

// Upper bounds of the RMSE to the sorted reference (8-bit steps), a little above what
// lavapipe measured when the goldens were made (the measured values in the comments).
// A scene or method without a row fails the test: record its bound when adding it.
struct SortedBound {
  const char* scene;
  const char* method;
  double rmse;
};
constexpr SortedBound kSortedBounds[] = {
    {"smoke", "alpha", 9.5},             // 8.333 (newest on top)
    {"smoke", "sorted", 0.0},
    {"smoke", "wboit", 4.5},             // 3.809
    {"smoke", "colored", 10.0},          // 8.718
    {"smoke", "colored-literal", 19.5},  // 17.898: dense smoke adds C * revealage ~ 0 over the darkened frame
    {"fire", "alpha", 0.0},              // additive is order-independent: alpha == sorted exactly
    {"fire", "sorted", 0.0},
    {"fire", "wboit", 17.0},             // 15.273 (the OIT tables average instead of adding)
    {"fire", "colored", 15.0},           // 13.273
    {"fire", "colored-literal", 25.0},   // 23.027
    {"shards", "alpha", 6.5},            // 5.832
    {"shards", "sorted", 0.0},
    {"shards", "wboit", 5.5},            // 4.494
    // 22.547: the tint of the transmitted background, which OVER and so the reference lack
    {"shards", "colored", 25.0},
    {"shards", "colored-literal", 24.0},  // 21.722
    {"teapot", "alpha", 11.0},  // 9.884: patch order puts the bottom's green inside over the body
    {"teapot", "sorted", 0.0},
    {"teapot", "wboit", 7.5},             // 6.695
    {"teapot", "colored", 7.5},           // 6.715 (transmission 0: dims what is behind as OVER does)
    {"teapot", "colored-literal", 22.0},  // 20.157
    {"complexity", "alpha", 9.0},         // 7.839 (quads submitted out of depth order)
    {"complexity", "sorted", 0.0},
    {"complexity", "wboit", 7.5},             // 6.711
    {"complexity", "colored", 24.0},          // 21.748: the quads are colour filters (t = their colour)
    {"complexity", "colored-literal", 40.0},  // 37.040
    // Document 002's exact methods at 8 layers (depth peeling: the 8 nearest, dual:
    // the 4 nearest and the 4 farthest). Where 8 are all the layers they are `sorted`
    // where that is exact; elsewhere they lose the layers beyond 8.
    {"smoke", "depth-peeling", 9.0},        // 7.965: dense smoke has dozens of layers
    {"smoke", "dual-depth-peeling", 9.5},   // 8.272
    {"fire", "depth-peeling", 17.0},        // 15.648: OVER of the 8 nearest, not additive
    {"fire", "dual-depth-peeling", 17.0},   // 15.269
    {"shards", "depth-peeling", 33.0},      // 31.067: coloured transmission, up to 12 layers
    {"shards", "dual-depth-peeling", 33.0}, // 31.051
    {"teapot", "depth-peeling", 1.0},       // 0.444: per pixel exact, `sorted` per triangle
    {"teapot", "dual-depth-peeling", 1.0},  // 0.444
    {"complexity", "depth-peeling", 0.6},   // 0.491: both exact, rounded apart
    {"complexity", "dual-depth-peeling", 0.6},  // 0.491
    // prefix-sum: exact, with each object's own per-surface model (shards: coloured
    // transmission, which OVER lacks; fire: OVER, where the reference adds), so it is
    // near sorted only where OVER is that model.
    {"smoke", "prefix-sum", 1.0},       // 0.560: per fragment where sorted orders whole particles
    {"fire", "prefix-sum", 18.5},       // 16.988: OVER, where the reference adds
    {"shards", "prefix-sum", 34.0},     // 31.114: the tint of the transmitted background, as colored
    {"teapot", "prefix-sum", 1.0},      // 0.454: per fragment where sorted orders triangle centroids
    {"complexity", "prefix-sum", 1.0},  // 0.576
    // Document 003's moment methods, and every method on its three scenes (measured
    // when these goldens were made). mboit and moment-transparency share their moment
    // code and give the same images.
    {"smoke", "mboit", 1.5},  // 1.093
    {"smoke", "moment-transparency", 1.5},  // 1.093
    {"smoke", "moment-transparency-mindepth", 1.5},  // 1.120
    {"smoke", "moment-transparency-mindepth-r16", 2.0},  // 1.232
    {"fire", "mboit", 18.5},  // 16.628
    {"fire", "moment-transparency", 18.5},  // 16.628
    {"fire", "moment-transparency-mindepth", 18.5},  // 16.627
    {"fire", "moment-transparency-mindepth-r16", 18.5},  // 16.626
    {"shards", "mboit", 4.0},  // 3.088
    {"shards", "moment-transparency", 4.0},  // 3.088
    {"shards", "moment-transparency-mindepth", 4.0},  // 3.278
    {"shards", "moment-transparency-mindepth-r16", 6.0},  // 4.945
    {"teapot", "mboit", 1.5},  // 0.857
    {"teapot", "moment-transparency", 1.5},  // 0.857
    {"teapot", "moment-transparency-mindepth", 1.5},  // 0.898
    {"teapot", "moment-transparency-mindepth-r16", 21.5},  // 19.296: R16 z_min: the red outside loses its weight (document 003's finding)
    {"complexity", "mboit", 2.0},  // 1.479
    {"complexity", "moment-transparency", 2.0},  // 1.479
    {"complexity", "moment-transparency-mindepth", 2.0},  // 1.479
    {"complexity", "moment-transparency-mindepth-r16", 15.0},  // 13.369: R16 z_min: rounded up or down, the nearest quad keeps or loses its weight
    {"cubes", "alpha", 4.5},  // 3.552
    {"cubes", "sorted", 0.0},  // 0.000
    {"cubes", "wboit", 10.5},  // 8.962
    {"cubes", "colored", 25.5},  // 22.897
    {"cubes", "colored-literal", 20.5},  // 18.268
    {"cubes", "depth-peeling", 3.0},  // 2.113
    {"cubes", "dual-depth-peeling", 3.0},  // 2.236
    {"cubes", "prefix-sum", 2.5},  // 1.913
    {"cubes", "mboit", 3.0},  // 2.347
    {"cubes", "moment-transparency", 3.0},  // 2.347
    {"cubes", "moment-transparency-mindepth", 3.0},  // 2.373
    {"cubes", "moment-transparency-mindepth-r16", 12.0},  // 10.493
    {"ice-in-cup", "alpha", 9.0},  // 7.645
    {"ice-in-cup", "sorted", 0.0},  // 0.000
    {"ice-in-cup", "wboit", 4.0},  // 3.366
    {"ice-in-cup", "colored", 25.5},  // 22.760
    {"ice-in-cup", "colored-literal", 17.5},  // 15.547
    {"ice-in-cup", "depth-peeling", 2.0},  // 1.219
    {"ice-in-cup", "dual-depth-peeling", 2.0},  // 1.219
    {"ice-in-cup", "prefix-sum", 2.0},  // 1.231
    {"ice-in-cup", "mboit", 3.5},  // 2.612
    {"ice-in-cup", "moment-transparency", 3.5},  // 2.612
    {"ice-in-cup", "moment-transparency-mindepth", 3.0},  // 2.096
    {"ice-in-cup", "moment-transparency-mindepth-r16", 13.0},  // 11.390
    {"magic-circle", "alpha", 6.5},  // 5.383
    {"magic-circle", "sorted", 0.0},  // 0.000
    {"magic-circle", "wboit", 6.5},  // 5.337
    {"magic-circle", "colored", 34.5},  // 31.000
    {"magic-circle", "colored-literal", 76.0},  // 68.782
    {"magic-circle", "depth-peeling", 6.5},  // 5.285
    {"magic-circle", "dual-depth-peeling", 6.0},  // 5.285
    {"magic-circle", "prefix-sum", 6.5},  // 5.364
    {"magic-circle", "mboit", 5.5},  // 4.542
    {"magic-circle", "moment-transparency", 5.5},  // 4.542
    {"magic-circle", "moment-transparency-mindepth", 7.0},  // 5.784: closer to the exact prefix-sum, which `sorted` (per triangle) is not here
    {"magic-circle", "moment-transparency-mindepth-r16", 15.0},  // 13.037
    // Document 001: WBOIT with MSAA equals WBOIT's average here (w = opacity; the
    // weight of Table 1 clamps to a constant at these depths), plus antialiased edges
    // the single-sampled reference lacks (every edge of the backdrop too). The additive
    // variants add every layer: far from OVER wherever the layers are dense.
    {"smoke", "wboit-msaa", 10.5},  // 9.336
    {"smoke", "wboit-msaa-per-pixel", 10.5},  // 9.442
    {"smoke", "wboit-msaa-additive", 51.0},  // 46.180
    {"smoke", "wboit-msaa-linear", 38.5},  // 34.666
    {"smoke", "wboit-msaa-exposure", 46.5},  // 41.835
    {"fire", "wboit-msaa", 20.5},  // 18.190
    {"fire", "wboit-msaa-per-pixel", 20.5},  // 18.210
    {"fire", "wboit-msaa-additive", 10.5},  // 9.115
    {"fire", "wboit-msaa-linear", 13.5},  // 12.051
    {"fire", "wboit-msaa-exposure", 16.5},  // 14.564
    {"shards", "wboit-msaa", 15.0},  // 13.363
    {"shards", "wboit-msaa-per-pixel", 15.0},  // 13.351
    {"shards", "wboit-msaa-additive", 51.5},  // 46.424
    {"shards", "wboit-msaa-linear", 33.5},  // 30.110
    {"shards", "wboit-msaa-exposure", 42.0},  // 37.918
    {"teapot", "wboit-msaa", 10.0},  // 9.035
    {"teapot", "wboit-msaa-per-pixel", 10.0},  // 9.055
    {"teapot", "wboit-msaa-additive", 51.5},  // 46.387
    {"teapot", "wboit-msaa-linear", 41.0},  // 37.165
    {"teapot", "wboit-msaa-exposure", 45.5},  // 41.032
    {"complexity", "wboit-msaa", 8.0},  // 6.860
    {"complexity", "wboit-msaa-per-pixel", 8.0},  // 6.868
    {"complexity", "wboit-msaa-additive", 77.5},  // 70.360
    {"complexity", "wboit-msaa-linear", 53.0},  // 47.919
    {"complexity", "wboit-msaa-exposure", 64.0},  // 57.735
    {"triangles", "wboit-msaa", 10.5},  // 9.337
    {"triangles", "wboit-msaa-per-pixel", 10.5},  // 9.376
    {"triangles", "wboit-msaa-additive", 18.5},  // 16.421
    {"triangles", "wboit-msaa-linear", 25.0},  // 22.689
    {"triangles", "wboit-msaa-exposure", 18.0},  // 16.241
    // Document 001's triangles: four parallel layers, where every exact method is sorted.
    {"triangles", "alpha", 13.0},  // 11.453
    {"triangles", "sorted", 0.0},  // 0.000
    {"triangles", "wboit", 8.0},  // 7.042
    {"triangles", "colored", 8.0},  // 7.042
    {"triangles", "colored-literal", 31.0},  // 27.898
    {"triangles", "depth-peeling", 0.8},  // 0.301
    {"triangles", "dual-depth-peeling", 0.8},  // 0.307
    {"triangles", "prefix-sum", 0.8},  // 0.286
    // Document 001's methods on document 003's scenes and document 003's on document 001's
    // triangles (made when the two branches met; viewed at 3x beside sorted).
    {"cubes", "wboit-msaa", 13.0},  // 11.368
    {"cubes", "wboit-msaa-per-pixel", 13.0},  // 11.440
    {"cubes", "wboit-msaa-additive", 62.0},  // 55.923
    {"cubes", "wboit-msaa-linear", 41.0},  // 37.049
    {"cubes", "wboit-msaa-exposure", 50.0},  // 45.126
    {"ice-in-cup", "wboit-msaa", 6.5},  // 5.789
    {"ice-in-cup", "wboit-msaa-per-pixel", 6.5},  // 5.727
    {"ice-in-cup", "wboit-msaa-additive", 69.5},  // 62.871
    {"ice-in-cup", "wboit-msaa-linear", 42.5},  // 38.276
    {"ice-in-cup", "wboit-msaa-exposure", 54.0},  // 49.053
    {"magic-circle", "wboit-msaa", 10.0},  // 8.928
    {"magic-circle", "wboit-msaa-per-pixel", 10.0},  // 8.908
    {"magic-circle", "wboit-msaa-additive", 51.0},  // 46.303
    {"magic-circle", "wboit-msaa-linear", 31.0},  // 27.951
    {"magic-circle", "wboit-msaa-exposure", 34.0},  // 30.653
    {"triangles", "mboit", 1.0},  // 0.476
    {"triangles", "moment-transparency", 1.0},  // 0.476
    {"triangles", "moment-transparency-mindepth", 1.0},  // 0.476
    {"triangles", "moment-transparency-mindepth-r16", 8.0},  // 7.193
    // Issue 19's compute tiles (particles only): compute-sorted is sorted's image within
    // one step a pixel (compute_tiles_test.cpp), compute-wboit wboit's.
    {"smoke", "compute-sorted", 0.1},   // 0.027
    {"smoke", "compute-wboit", 4.5},    // 3.810 (wboit: 3.809)
    {"fire", "compute-sorted", 0.1},    // 0.008
    {"fire", "compute-wboit", 17.0},    // 15.271 (wboit: 15.273)
};

const SortedBound* FindBound(const char* scene, const char* method) {
  for (const SortedBound& b : kSortedBounds)
    if (std::string(b.scene) == scene && std::string(b.method) == method) return &b;
  return nullptr;
}

class GoldenTest : public GpuTest {
 protected:
  std::vector<uint8_t> Render(const renderer::SceneInfo& scene, const MethodInfo& method) {
    std::string error;
    auto t = Translucency::Create(device.Get(), context.Get(), GoldenSettings(scene), &error);
    EXPECT_NE(t, nullptr) << error;
    if (!t || !t->Accepts(method)) return {};  // empty: the method does not draw the scene by design
    for (int i = 0; i < GoldenFrames(scene); ++i) EXPECT_TRUE(t->RenderFrame(method)) << t->error();
    return t->ReadFrame();
  }
};

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
  for (const renderer::SceneInfo* scene : renderer::Scenes()) {
    const std::vector<uint8_t> sorted = Render(*scene, *renderer::oit::FindMethod("sorted"));
    for (const MethodInfo* method : renderer::oit::Methods()) {
      // Lavapipe breaks the linked lists along triangle edges (fragment_buffer_test.cpp):
      // no golden image of that method from it.
      if (std::string(method->name) == "linked-list" && std::string(device->GetAdapterName()).find("llvmpipe") == 0)
        continue;
      const std::string name = std::string(scene->name) + "_" + method->name;
      SCOPED_TRACE(name);
      const std::vector<uint8_t> image = Render(*scene, *method);
      if (image.empty() && !HasFailure()) continue;  // refused by design (Translucency::Accepts)
      ASSERT_EQ(image.size(), size_t(kWidth) * kHeight * 4);
      const double toSorted = renderer::Rmse(image, sorted);
      std::printf("%-24s RMSE to sorted %.3f\n", name.c_str(), toSorted);
      const SortedBound* bound = FindBound(scene->name, method->name);
      ASSERT_NE(bound, nullptr) << "no recorded bound of the RMSE to sorted";
      EXPECT_LE(toSorted, bound->rmse + 1e-9);
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
