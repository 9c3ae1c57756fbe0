// replay: the translucency demos of document 000 (SPEC.md), headless and deterministic.
//
//   replay --list-methods | --list-scenes
//       one line per registered transparency method (name, what it needs of the device,
//       summary) or scene: the registries renderer/oit and renderer/scenes.h.
//   replay --demo SCENE --method METHOD [--frames N] [--size WxH] [--peel-layers N] [--layer K] --out DIR
//       renders frames 0..N-1 (fixed time step, seeded, camera a function of the frame index)
//       and writes DIR/<scene>_<method>_<frame>.png for the last frame (--all-frames: every frame).
//       --peel-layers: the layers the peeling methods keep (default 8); --layer K: a method
//       that keeps layers (depth-peeling) shows layer K alone, over neutral grey, in
//       DIR/<scene>_<method>_layer<K>_<frame>.png.
//       fire: flames drawn with additive blending for alpha and sorted (order-independent).
//   replay --figures --out DIR [--size WxH] [--frames N] [--document 001|003]
//       fig1_smoke_alpha_wboit.png (alpha | WBOIT), fig_shards_wboit_colored_sorted.png
//       (WBOIT | colored | sorted), fig_fire_additive_wboit_colored.png,
//       fig3_teapot_alpha_sorted_wboit.png (document 002's teapot: alpha | sorted | WBOIT),
//       document 002's figures with depth peeling on its teapot (shards where there is no
//       teapot scene): fig3_<scene>_depth_peeling_layers_0-3.png (Fig. 3: layers 0-3, each
//       alone over neutral grey) and fig6_<scene>_depth_peeling_1_2_4_8_exact.png (Fig. 6:
//       1, 2, 4 and 8 layers and the exact composite, every layer peeled), every
//       method's RMSE / PSNR against the sorted reference, and Fig. 6's against the exact one;
//       document 003's figures (WriteMomentFigures): exact | Moment Transparency | with the
//       minimum-depth correction on its three scenes, the m sweep on its cubes, R32 | R16
//       nearest depth, RMSE / PSNR against the exact result, the extra target's memory (its
//       scenes are measured there only, against the exact result instead of sorted).
//       --document 003: that document's figures alone.
//       document 001's on its triangles against the exact composite (prefix-sum):
//       fig001_triangles_opacity1_exact_wboit_msaa.png (opacity 1 hides nothing),
//       fig001_triangles_opacity_sweep_exact_above_wboit_msaa_below.png (0.1 .. 1, with RMSE),
//       fig001_triangles_per_sample_per_pixel_differing.png (the differing pixels counted),
//       fig001_triangles_wboit_additive_linear_exposure.png (the discussion's variants);
//       --document 001: only these
//   replay --bench [--scene demo|paper|heavy|complexity] [--frames N] [--warmup N] [--size WxH]
//                  [--fragment-sizing exact|late|redraw] [--msaa 4|8] [--methods A,B,...]
//       per registered method (or those --methods names): FPS and frame ms from the GPU (TIMESTAMP queries inside a
//       TIMESTAMP_DISJOINT query, median over N frames), per-pass GPU ms (the "3D pass" is
//       the method's pass that draws the translucent objects, Method::FragmentPass), CPU ms per frame
//       (RenderFrame's recording and submission, median), wall ms; WBOIT/alpha ratio; the
//       compute-tile methods' translucent passes against alpha's (issue 19).
//       demo:  the smoke and shards demos at --size (default 640x360);
//       paper: 1280x720, smoke of a few thousand particles over the opaque scene (Fig. 2);
//       heavy: 1920x1080, 1M particles plus 10k instanced shards in one frame, then the
//       same particles alone (the scene the compute-tile methods draw);
//       complexity: the complexity scene at depth complexity 1, 4, 16, 32, 64 at --size.
//       A method that refuses a scene is skipped with its reason; a method of more than two
//       passes also gets a line of its passes' GPU ms by name.
//       --warmup defaults to the updates the smoke needs to reach its steady state.
//   replay --compare [--size WxH] [--out DIR] [--frames N] [--peel-layers N]
//       every registered method on every registered scene at each scene's default frame,
//       against the scene's exact reference (renderer/comparison.h): RMSE, PSNR, SSIM,
//       pixels off by > 2/255, bytes per pixel, fragments, GPU ms (the median of N timed
//       draws of the compared frame, default 5) -> DIR/comparison.md,
//       DIR/compare_grid.png and DIR/pareto_<scene>.png (app/compare_report.h).
//       --peel-layers: the most layers the peeling methods get (default 64; a scene
//       with fewer gets its own count).
//   --min-depth-slope M (--demo): document 003's m for moment-transparency-mindepth (default 100,
//       per scene unit of view depth).
//   --msaa 4|8 (--demo, --figures, --bench): the samples of the multisampled methods
//       (wboit-msaa and its variants; default 4; 8 refused where the device has none).
//   --fragment-sizing (--demo, --bench): how prefix-sum sizes its fragment buffer: exact
//       (default: each frame's own total, the CPU waits for it), late (earlier frames'
//       totals, no wait; a frame that outgrows the buffer loses fragments, reported) or
//       redraw (the same, the frame's total read at its end; a frame that did not fit is
//       drawn again with the buffer grown).
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli_args.h"
#include "compare_report.h"
#include "renderer/comparison.h"
#include "renderer/translucency.h"
#include "replay_window.h"
#include "rhi/rhi.h"

using renderer::oit::MethodInfo;

namespace {

int gErrors = 0;

[[noreturn]] void Fail(const std::string& what) {
  std::fprintf(stderr, "replay: %s\n", what.c_str());
  std::exit(1);
}

// The integer an option's value spells, in [min, max], else a one-line failure.
int64_t IntegerOption(const std::string& option, const std::string& text, int64_t min, int64_t max) {
  std::string error;
  std::optional<int64_t> value = cli::ParseInteger(option, text, min, max, &error);
  if (!value) Fail(error);
  return *value;
}

// WxH for --size.
void SizeOption(const std::string& text, uint32_t* width, uint32_t* height) {
  std::string error;
  std::optional<std::vector<int64_t>> size = cli::ParseIntegers("--size", text, 'x', 2, 1, 16384, &error);
  if (!size) Fail(error);
  *width = static_cast<uint32_t>((*size)[0]);
  *height = static_cast<uint32_t>((*size)[1]);
}

void MakeOutFolder(const std::string& folder) {
  if (std::string error; !cli::MakeFolder("--out", folder, &error)) Fail(error);
}

struct Options {
  std::string demo = "smoke";  // a scene of renderer::Scenes()
  const MethodInfo* method = renderer::oit::FindMethod("wboit");
  int frames = -1;
  uint32_t width = 640, height = 360;
  std::string out = "out/replay";
  bool figures = false, bench = false, compare = false, allFrames = false, listMethods = false, listScenes = false;
  std::string scene = "demo";  // --bench: demo | paper | heavy
  int warmup = -1;
  uint32_t peelLayers = renderer::oit::kDefaultPeelLayers;
  bool peelLayersGiven = false;
  int layer = -1;  // --layer: the layer shown alone
  renderer::oit::FragmentStorage fragmentStorage;  // --fragment-sizing
  std::string document;  // --figures --document 001|003: that document's figures alone
  float minDepthSlope = renderer::oit::kDefaultMinDepthSlope;  // --min-depth-slope: document 003's m
  uint32_t msaaSamples = renderer::oit::kDefaultMsaaSamples;  // --msaa
  std::vector<const MethodInfo*> benchMethods;  // --methods: --bench times these alone (empty: all)
};

// The settings of a replay of `scene` at --size with the methods' options.
renderer::TranslucencySettings Settings(const Options& o, const std::string& scene) {
  renderer::TranslucencySettings s;
  s.scene = scene;
  s.width = o.width, s.height = o.height;
  s.peelLayers = o.peelLayers;
  s.fragmentStorage = o.fragmentStorage;
  s.msaaSamples = o.msaaSamples;
  s.minDepthSlope = o.minDepthSlope;
  return s;
}

std::unique_ptr<renderer::Translucency> Make(rhi::Device* device, rhi::DeviceContext* ctx,
                                             renderer::TranslucencySettings settings) {
  std::string error;
  auto t = renderer::Translucency::Create(device, ctx, settings, &error);
  if (!t) Fail(error);
  return t;
}

void Render(renderer::Translucency& t, const MethodInfo& method) {
  if (!t.RenderFrame(method)) Fail(t.error());
}

// Renders frames 0..frames-1 with one method and returns the last frame.
std::vector<uint8_t> Replay(rhi::Device* device, rhi::DeviceContext* ctx, const renderer::TranslucencySettings& s,
                            const MethodInfo& method, int frames) {
  auto t = Make(device, ctx, s);
  for (int i = 0; i < frames; ++i) Render(*t, method);
  return t->ReadFrame();
}

// The frames a replay of `settings` renders: --frames, else the scene's default.
int Frames(const Options& o, const std::string& scene) { return o.frames > 0 ? o.frames : renderer::FindScene(scene)->defaultFrames; }

const MethodInfo& Method(const char* name) {
  const MethodInfo* m = renderer::oit::FindMethod(name);
  if (!m) Fail(std::string("no method ") + name);
  return *m;
}

void WritePng(const std::string& path, const std::vector<uint8_t>& rgba, uint32_t w, uint32_t h) {
  if (!stbi_write_png(path.c_str(), int(w), int(h), 4, rgba.data(), int(w * 4))) Fail("cannot write " + path);
  std::printf("wrote %s (%ux%u)\n", path.c_str(), w, h);
}

// Images of equal height side by side, with a 4-pixel white gap.
std::vector<uint8_t> SideBySide(const std::vector<std::vector<uint8_t>>& images, uint32_t w, uint32_t h,
                                uint32_t* outWidth) {
  const uint32_t gap = 4, total = uint32_t(images.size()) * w + gap * uint32_t(images.size() - 1);
  std::vector<uint8_t> out(size_t(total) * h * 4, 255);
  for (size_t i = 0; i < images.size(); ++i)
    for (uint32_t y = 0; y < h; ++y)
      std::memcpy(&out[(size_t(y) * total + i * (w + gap)) * 4], &images[i][size_t(y) * w * 4], w * 4);
  *outWidth = total;
  return out;
}

int RunOne(rhi::Device* device, rhi::DeviceContext* ctx, const Options& o) {
  renderer::TranslucencySettings s = Settings(o, o.demo);
  s.showLayer = o.layer;
  const int frames = Frames(o, o.demo);
  auto t = Make(device, ctx, s);
  MakeOutFolder(o.out);
  for (int i = 0; i < frames; ++i) {
    Render(*t, *o.method);
    if (o.allFrames || i == frames - 1) {
      char name[256];
      const std::string layer = o.layer < 0 ? "" : "_layer" + std::to_string(o.layer);
      std::snprintf(name, sizeof name, "%s_%s%s_%04d.png", o.demo.c_str(), o.method->name, layer.c_str(), i);
      WritePng((std::filesystem::path(o.out) / name).string(), t->ReadFrame(), o.width, o.height);
    }
  }
  return 0;
}

int ListMethods() {
  int width = 0;  // the longest name's
  for (const MethodInfo* m : renderer::oit::Methods()) width = std::max(width, int(std::strlen(m->name)));
  for (const MethodInfo* m : renderer::oit::Methods())
    std::printf("%-*s needs: %-44s %s\n", width, m->name, renderer::oit::DescribeNeeds(m->needs).c_str(), m->summary);
  return 0;
}

int ListScenes() {
  for (const renderer::SceneInfo* s : renderer::Scenes())
    std::printf("%-12s %4d frames  %s\n", s->name, s->defaultFrames, s->summary);
  return 0;
}

// Document 002's figures with depth peeling, on its teapot where that scene exists
// (another branch adds it), else on the shards.
//   Fig. 3: layers 0-3, each alone over neutral grey.
//   Fig. 6: 1, 2, 4 and 8 layers against the exact composite: kExactLayers layers, exact
//           when the last of them is empty (the figure says so when it is not).
void WritePeelingFigures(rhi::Device* device, rhi::DeviceContext* ctx, const Options& o) {
  constexpr uint32_t kExactLayers = 32;
  const std::string scene = renderer::FindScene("teapot") ? "teapot" : "shards";
  const MethodInfo& peeling = Method("depth-peeling");
  renderer::TranslucencySettings s;
  s.scene = scene;
  s.width = o.width, s.height = o.height;
  const int frames = Frames(o, scene);
  const std::filesystem::path out(o.out);
  uint32_t w = 0;

  std::vector<std::vector<uint8_t>> layers;
  for (int k = 0; k < 4; ++k) {
    s.showLayer = k;
    layers.push_back(Replay(device, ctx, s, peeling, frames));
  }
  s.showLayer = -1;
  auto fig3 = SideBySide(layers, o.width, o.height, &w);
  WritePng((out / ("fig3_" + scene + "_depth_peeling_layers_0-3.png")).string(), fig3, w, o.height);

  s.peelLayers = kExactLayers;
  auto exact = Make(device, ctx, s);
  for (int i = 0; i < frames; ++i) Render(*exact, peeling);
  const std::vector<uint8_t> exactImage = exact->ReadFrame();
  const std::vector<uint64_t> samples = exact->MethodInstance(peeling)->LayerSamples(ctx);
  if (samples.empty() || samples.back() != 0)
    std::printf("%s: layer %u is not empty: the exact panel misses what lies behind it\n", scene.c_str(),
                kExactLayers - 1);
  std::vector<std::vector<uint8_t>> panels;
  for (uint32_t n : {1u, 2u, 4u, 8u}) {
    s.peelLayers = n;
    panels.push_back(Replay(device, ctx, s, peeling, frames));
    const double rmse = renderer::Rmse(panels.back(), exactImage);
    std::printf("%-10s %-20s %10.3f %10.2f  (%u layers against the exact composite)\n", scene.c_str(), peeling.name,
                rmse, renderer::Psnr(rmse), n);
  }
  panels.push_back(exactImage);
  auto fig6 = SideBySide(panels, o.width, o.height, &w);
  WritePng((out / ("fig6_" + scene + "_depth_peeling_1_2_4_8_exact.png")).string(), fig6, w, o.height);
}

// Document 003's scenes: still, measured against the exact result (WriteMomentFigures),
// not against `sorted`, which orders whole triangles (a floor quad under a decal).
constexpr const char* kDocument003Scenes[] = {"cubes", "ice-in-cup", "magic-circle"};

bool IsDocument003Scene(const std::string& scene) {
  return std::find(std::begin(kDocument003Scenes), std::end(kDocument003Scenes), scene) != std::end(kDocument003Scenes);
}

// Document 003's figures, each scene against the exact result (prefix-sum, document 004):
//   doc003_<scene>_exact_mt_mindepth.png   exact | Moment Transparency | with the correction
//   doc003_cubes_m_1_5_25_50_75_100_150_200.png   the m sweep of the thesis's Figs. 4.7-4.22
//   doc003_<scene>_mindepth_r32_r16.png     the nearest depth in R32_FLOAT | in R16_FLOAT
// with every moment method's RMSE / PSNR against the exact image, the sweep's too, and
// the memory of the correction's extra target at 1920x1080 and 3840x2160.
void WriteMomentFigures(rhi::Device* device, rhi::DeviceContext* ctx, const Options& o) {
  const std::filesystem::path out(o.out);
  const char* kMethods[] = {"wboit", "mboit", "moment-transparency", "moment-transparency-mindepth",
                            "moment-transparency-mindepth-r16"};
  std::printf("\ndocument 003 against the exact result (prefix-sum), %ux%u\n", o.width, o.height);
  std::printf("%-13s %-33s %10s %10s\n", "scene", "method", "RMSE", "PSNR dB");
  uint32_t w = 0;
  for (const char* scene : kDocument003Scenes) {
    renderer::TranslucencySettings s;
    s.scene = scene;
    s.width = o.width, s.height = o.height;
    const int frames = renderer::FindScene(scene)->defaultFrames;  // still scenes: --frames is the others'
    const std::vector<uint8_t> exact = Replay(device, ctx, s, Method("prefix-sum"), frames);
    std::map<std::string, std::vector<uint8_t>> images;
    for (const char* name : kMethods) {
      images[name] = Replay(device, ctx, s, Method(name), frames);
      const double rmse = renderer::Rmse(images[name], exact);
      std::printf("%-13s %-33s %10.3f %10.2f\n", scene, name, rmse, renderer::Psnr(rmse));
    }
    auto fig = SideBySide({exact, images["moment-transparency"], images["moment-transparency-mindepth"]}, o.width,
                          o.height, &w);
    WritePng((out / ("doc003_" + std::string(scene) + "_exact_mt_mindepth.png")).string(), fig, w, o.height);
    fig = SideBySide({images["moment-transparency-mindepth"], images["moment-transparency-mindepth-r16"]}, o.width,
                     o.height, &w);
    WritePng((out / ("doc003_" + std::string(scene) + "_mindepth_r32_r16.png")).string(), fig, w, o.height);
    // The m sweep (document 003's Figs. 4.7-4.22 on its cubes), measured on every scene.
    std::vector<std::vector<uint8_t>> sweep;
    std::printf("%-13s m sweep, RMSE to exact:", scene);
    for (float m : {1.0f, 5.0f, 25.0f, 50.0f, 75.0f, 100.0f, 150.0f, 200.0f}) {
      s.minDepthSlope = m;
      sweep.push_back(Replay(device, ctx, s, Method("moment-transparency-mindepth"), frames));
      std::printf(" m=%g %.3f", m, renderer::Rmse(sweep.back(), exact));
    }
    std::printf("\n");
    if (std::string(scene) == "cubes") {
      fig = SideBySide(sweep, o.width, o.height, &w);
      WritePng((out / "doc003_cubes_m_1_5_25_50_75_100_150_200.png").string(), fig, w, o.height);
    }
  }
  // The extra target: the correction's method less plain Moment Transparency, as the
  // methods report their memory (document 003: 7.91 MiB and 31.6 MiB in 32 bits).
  for (const auto& [width, height] : {std::pair{1920u, 1080u}, std::pair{3840u, 2160u}}) {
    renderer::oit::MethodSetup setup;
    setup.device = device;
    setup.frame = {width, height, 1};
    setup.objectCount = 1;
    std::string error;
    const auto bytes = [&](const char* name) {
      auto method = Method(name).create(Method(name), setup, &error);
      if (!method) Fail(error);
      return method->MemoryBytes();
    };
    const uint64_t plain = bytes("moment-transparency");
    std::printf("%ux%u: Moment Transparency %.2f MiB; the min-depth target R32_FLOAT %.2f MiB, R16_FLOAT %.2f MiB\n",
                width, height, plain / 1048576.0, (bytes("moment-transparency-mindepth") - plain) / 1048576.0,
                (bytes("moment-transparency-mindepth-r16") - plain) / 1048576.0);
  }
}

// `images` (each w x h) in rows of `perRow`, with 4-pixel white gaps.
std::vector<uint8_t> Grid(const std::vector<std::vector<uint8_t>>& images, size_t perRow, uint32_t w, uint32_t h,
                          uint32_t* outWidth, uint32_t* outHeight) {
  const uint32_t gap = 4, rows = uint32_t((images.size() + perRow - 1) / perRow);
  std::vector<uint8_t> out;
  for (uint32_t r = 0; r < rows; ++r) {
    std::vector<std::vector<uint8_t>> row(images.begin() + r * perRow,
                                          images.begin() + std::min(images.size(), (r + 1) * perRow));
    while (row.size() < perRow) row.emplace_back(size_t(w) * h * 4, 255);
    if (r > 0) out.insert(out.end(), size_t(*outWidth) * gap * 4, 255);
    const std::vector<uint8_t> strip = SideBySide(row, w, h, outWidth);
    out.insert(out.end(), strip.begin(), strip.end());
  }
  *outHeight = rows * h + (rows - 1) * gap;
  return out;
}

// The pixels where two frames differ, in red over `a` at a quarter of its brightness.
std::vector<uint8_t> DifferingPixels(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, size_t* count) {
  std::vector<uint8_t> map(a.size());
  *count = 0;
  for (size_t i = 0; i < a.size(); i += 4) {
    const bool differs = a[i] != b[i] || a[i + 1] != b[i + 1] || a[i + 2] != b[i + 2];
    *count += differs;
    for (int c = 0; c < 3; ++c) map[i + c] = differs ? (c == 0 ? 255 : 0) : uint8_t(a[i + c] / 4);
    map[i + 3] = 255;
  }
  return map;
}

// Document 001's figures on its triangles, against the exact composite (prefix-sum):
//   the failure of opacity 1 (the front blue triangle): exact | WBOIT with MSAA;
//   an opacity sweep, every triangle at 0.1 .. 1: exact above, WBOIT below;
//   what the per-sample resolve buys: per sample | per pixel | the pixels that differ;
//   the variants of its discussion: WBOIT | additive | additive linear (sRGB) | exposure.
void WriteWboitMsaaFigures(rhi::Device* device, rhi::DeviceContext* ctx, const Options& o) {
  const MethodInfo &exact = Method("prefix-sum"), &wboit = Method("wboit-msaa");
  const std::filesystem::path out(o.out);
  const uint32_t w = o.width, h = o.height;
  uint32_t fw = 0, fh = 0;
  const renderer::TranslucencySettings s = Settings(o, "triangles");
  const std::vector<std::vector<uint8_t>> failure = {Replay(device, ctx, s, exact, 1), Replay(device, ctx, s, wboit, 1)};
  const auto failureFigure = SideBySide(failure, w, h, &fw);
  WritePng((out / "fig001_triangles_opacity1_exact_wboit_msaa.png").string(), failureFigure, fw, h);

  std::vector<std::vector<uint8_t>> exactRow, wboitRow;
  for (float opacity : {0.1f, 0.25f, 0.5f, 0.75f, 1.0f}) {
    renderer::TranslucencySettings sweep = s;
    sweep.frontOpacity = sweep.triangleOpacity = opacity;
    exactRow.push_back(Replay(device, ctx, sweep, exact, 1));
    wboitRow.push_back(Replay(device, ctx, sweep, wboit, 1));
    const double rmse = renderer::Rmse(wboitRow.back(), exactRow.back());
    std::printf("%-10s %-20s %10.3f %10.2f  (every triangle at opacity %.2f, against prefix-sum)\n", "triangles",
                wboit.name, rmse, renderer::Psnr(rmse), opacity);
  }
  exactRow.insert(exactRow.end(), wboitRow.begin(), wboitRow.end());
  auto sweepFigure = Grid(exactRow, 5, w, h, &fw, &fh);
  WritePng((out / "fig001_triangles_opacity_sweep_exact_above_wboit_msaa_below.png").string(), sweepFigure, fw, fh);

  const std::vector<uint8_t>& perSample = failure[1];
  const std::vector<uint8_t> perPixel = Replay(device, ctx, s, Method("wboit-msaa-per-pixel"), 1);
  size_t differing = 0;
  const std::vector<uint8_t> edges = DifferingPixels(perSample, perPixel, &differing);
  std::printf("triangles: %zu of %u pixels differ between the per-sample and the per-pixel resolve (%ux MSAA)\n",
              differing, w * h, o.msaaSamples);
  const auto edgeFigure = SideBySide({perSample, perPixel, edges}, w, h, &fw);
  WritePng((out / "fig001_triangles_per_sample_per_pixel_differing.png").string(), edgeFigure, fw, h);
  int largest = 0;  // how far apart the two resolves are there, in 8-bit steps
  for (size_t i = 0; i < perSample.size(); i += 4)
    for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(int(perSample[i + c]) - int(perPixel[i + c])));
  std::printf("triangles: the two resolves differ by up to %d steps of 255 in a channel\n", largest);

  std::vector<std::vector<uint8_t>> variants;
  for (const char* name : {"wboit-msaa", "wboit-msaa-additive", "wboit-msaa-linear", "wboit-msaa-exposure"})
    variants.push_back(Replay(device, ctx, s, Method(name), 1));
  const std::vector<std::pair<const char*, const std::vector<uint8_t>*>> measured = {
      {"wboit-msaa", &variants[0]},          {"wboit-msaa-per-pixel", &perPixel},
      {"wboit-msaa-additive", &variants[1]}, {"wboit-msaa-linear", &variants[2]},
      {"wboit-msaa-exposure", &variants[3]}};
  for (const auto& [name, image] : measured) {
    const double rmse = renderer::Rmse(*image, failure[0]);
    std::printf("%-10s %-20s %10.3f %10.2f  (against prefix-sum)\n", "triangles", name, rmse, renderer::Psnr(rmse));
  }
  const auto variantFigure = SideBySide(variants, w, h, &fw);
  WritePng((out / "fig001_triangles_wboit_additive_linear_exposure.png").string(), variantFigure, fw, h);
}

// Frame `frames` - 1 of the replay as every method draws it: the frames before it run
// once (the objects' updates do not depend on the method), then each method draws
// that frame again (RenderFrameAgain), as a replay of its own would
// (tests/replay/comparison_test.cpp, RenderFrameAgainTest). The updates count the
// particles, which `sorted` needs to draw a frame again. A method that does not draw
// the scene by design (Translucency::Accepts) has no image.
std::map<std::string, std::vector<uint8_t>> LastFrameOfEveryMethod(rhi::Device* device, rhi::DeviceContext* ctx,
                                                                   renderer::TranslucencySettings s, int frames) {
  s.countParticles = true;
  auto t = Make(device, ctx, s);
  for (int i = 0; i < frames; ++i) Render(*t, Method("alpha"));
  std::map<std::string, std::vector<uint8_t>> images;
  for (const MethodInfo* m : renderer::oit::Methods()) {
    if (!t->Accepts(*m)) continue;
    if (!t->RenderFrameAgain(*m)) Fail(t->error());
    images[m->name] = t->ReadFrame();
  }
  return images;
}

int RunFigures(rhi::Device* device, rhi::DeviceContext* ctx, const Options& o) {
  MakeOutFolder(o.out);
  if (o.document == "001") return WriteWboitMsaaFigures(device, ctx, o), 0;
  if (o.document == "003") return WriteMomentFigures(device, ctx, o), 0;
  std::printf("%-10s %-20s %10s %10s\n", "demo", "method", "RMSE", "PSNR dB");
  // Every scene with every method, measured against the sorted reference; the
  // figures are the source document's, each of named methods.
  struct Figure {
    const char* scene;
    const char* file;
    std::vector<const char*> methods;
  };
  const Figure figures[] = {{"smoke", "fig1_smoke_alpha_wboit.png", {"alpha", "wboit"}},
                            {"smoke", "smoke_wboit_colored_sorted.png", {"wboit", "colored", "sorted"}},
                            {"smoke", "fig_smoke_sorted_wboit_in_compute_tiles.png",
                             {"sorted", "compute-sorted", "wboit", "compute-wboit"}},
                            {"fire", "fig_fire_additive_wboit_colored.png", {"alpha", "wboit", "colored"}},
                            {"shards", "fig_shards_wboit_colored_sorted.png", {"wboit", "colored", "sorted"}},
                            {"teapot", "fig3_teapot_alpha_sorted_wboit.png", {"alpha", "sorted", "wboit"}}};
  for (const renderer::SceneInfo* scene : renderer::Scenes()) {
    if (IsDocument003Scene(scene->name)) continue;  // WriteMomentFigures measures them against the exact result
    const renderer::TranslucencySettings s = Settings(o, scene->name);
    const int frames = Frames(o, scene->name);
    std::map<std::string, std::vector<uint8_t>> images = LastFrameOfEveryMethod(device, ctx, s, frames);
    for (const MethodInfo* m : renderer::oit::Methods()) {
      if (!images.count(m->name)) {
        std::printf("%-10s %-20s %21s\n", scene->name, m->name, "(draws particles only)");
        continue;
      }
      double rmse = renderer::Rmse(images[m->name], images["sorted"]);
      std::printf("%-10s %-20s %10.3f %10.2f\n", scene->name, m->name, rmse, renderer::Psnr(rmse));
    }
    for (const Figure& f : figures) {
      if (std::string(f.scene) != scene->name) continue;
      std::vector<std::vector<uint8_t>> panels;
      for (const char* name : f.methods) panels.push_back(images.at(Method(name).name));
      uint32_t w = 0;
      auto fig = SideBySide(panels, o.width, o.height, &w);
      WritePng((std::filesystem::path(o.out) / f.file).string(), fig, w, o.height);
    }
  }
  WritePeelingFigures(device, ctx, o);
  WriteMomentFigures(device, ctx, o);
  WriteWboitMsaaFigures(device, ctx, o);
  return 0;
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

struct BenchCase {
  std::string name;
  renderer::TranslucencySettings settings;
};

// The scenes of --bench: the demos at --size, or the paper-like and heavy scenes.
std::vector<BenchCase> BenchCases(const Options& o) {
  std::vector<BenchCase> cases;
  if (o.scene == "paper") {
    renderer::TranslucencySettings s;
    s.scene = "smoke";
    s.width = 1280, s.height = 720;
    s.rule = {32, 2, 40, 60};  // steady state ~4,500 particles (the paper's demo: a few thousand)
    cases.push_back({"paper", s});
  } else if (o.scene == "heavy") {
    renderer::TranslucencySettings s;
    s.scene = "smoke";
    s.width = 1920, s.height = 1080;
    s.rule = {4096, 8, 20, 22};  // steady state ~1.0M particles (4096 * (1 + 8 * 30.5))
    s.particleSize = 0.05f;
    s.extraShards = 10000;
    cases.push_back({"heavy", s});
    // The same particles alone: the scene the compute-tile methods draw (particles only).
    s.extraShards = 0;
    cases.push_back({"heavy smoke", s});
  } else if (o.scene == "complexity") {
    // Document 004's sweep: the same quads at depth complexity 1 to 64, at --size.
    for (uint32_t complexity : {1u, 4u, 16u, 32u, 64u}) {
      renderer::TranslucencySettings s;
      s.scene = "complexity";
      s.width = o.width, s.height = o.height;
      s.depthComplexity = complexity;
      s.peelLayers = complexity;  // depth peeling exact at every complexity (dual: the same layers)
      cases.push_back({"complexity " + std::to_string(complexity), s});
    }
  } else {
    for (const char* scene : {"smoke", "shards"}) {
      renderer::TranslucencySettings s;
      s.scene = scene;
      s.width = o.width, s.height = o.height;
      cases.push_back({scene, s});
    }
  }
  return cases;
}

// The timed samples of one method (medians are taken at the end).
struct MethodSamples {
  std::vector<double> wall, cpu, opaque, update, fragmentPass, laterPasses, methodPasses, gpu, fragments;
  std::vector<std::vector<double>> passes;  // [pass][frame]
};

// Renders and times one frame of `t`; the GPU times only when its timestamps came back.
void TimeFrame(renderer::Translucency& t, const MethodInfo& method, MethodSamples& samples) {
  auto start = std::chrono::steady_clock::now();
  Render(t, method);
  auto recorded = std::chrono::steady_clock::now();
  renderer::PassTimes times = t.LastTimes();  // waits for the GPU
  auto done = std::chrono::steady_clock::now();
  samples.cpu.push_back(std::chrono::duration<double, std::milli>(recorded - start).count());
  samples.wall.push_back(std::chrono::duration<double, std::milli>(done - start).count());
  if (!times.valid) return;
  samples.opaque.push_back(times.opaqueMs), samples.update.push_back(times.updateMs);
  double later = 0;  // the passes after the fragment pass (a pass before it is in the total)
  for (size_t i = times.fragmentPass + 1; i < times.methodPassMs.size(); ++i) later += times.methodPassMs[i];
  samples.fragmentPass.push_back(times.methodPassMs.at(times.fragmentPass)), samples.laterPasses.push_back(later);
  double allPasses = 0;  // every pass of the method: what it costs over the opaque frame and the updates
  for (double ms : times.methodPassMs) allPasses += ms;
  samples.methodPasses.push_back(allPasses);
  samples.passes.resize(times.methodPassMs.size());
  for (size_t i = 0; i < times.methodPassMs.size(); ++i) samples.passes[i].push_back(times.methodPassMs[i]);
  samples.gpu.push_back(times.totalMs), samples.fragments.push_back(double(times.fragmentPassInvocations));
}

// A replay of one method warmed up for the bench, or null (and `why`) when the
// method refuses the scene.
struct BenchReplay {
  const MethodInfo* method;
  std::unique_ptr<renderer::Translucency> replay;
  MethodSamples samples;
};

std::vector<BenchReplay> WarmedUpReplays(rhi::Device* device, rhi::DeviceContext* ctx,
                                         const renderer::TranslucencySettings& settings, int warmup,
                                         const std::vector<const MethodInfo*>& methods) {
  std::vector<BenchReplay> replays;
  for (const MethodInfo* method : methods) {
    auto t = Make(device, ctx, settings);
    bool made = true;
    for (int i = 0; i < warmup && made; ++i) {
      made = t->RenderFrame(*method);
      t->LastTimes();
    }
    if (!made) {
      std::printf("%-20s skipped: %s\n", method->name, t->error().c_str());
      continue;
    }
    replays.push_back({method, std::move(t), {}});
  }
  return replays;
}

void PrintBenchRow(BenchReplay& r, const renderer::TranslucencySettings& base, bool particles) {
  renderer::Translucency& t = *r.replay;
  const MethodSamples& m = r.samples;
  const double gpuMs = Median(m.gpu);
  const renderer::oit::Method* method = t.MethodInstance(*r.method);
  const double mib = double(method->MemoryBytes()) / (1024.0 * 1024.0);
  // The live count of the last frame (an extra SO_STATISTICS frame, not timed).
  uint64_t live = 0;
  if (particles) {
    Render(t, Method("sorted"));  // a back-to-front method always counts
    live = t.particleCount();
    t.LastTimes();
  }
  // The 3D pass's fill rate: fragments shaded (and blended) per second.
  const double pass3dMs = Median(m.fragmentPass), fragmentCount = Median(m.fragments);
  std::printf("%-20s %9.1f %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %9llu %10u %9.2f %9.2f %10.2f\n", r.method->name,
              gpuMs > 0 ? 1000.0 / gpuMs : 0.0, gpuMs, Median(m.opaque), Median(m.update), pass3dMs,
              Median(m.laterPasses), Median(m.cpu), Median(m.wall), static_cast<unsigned long long>(live),
              base.scene == "shards" ? base.shardCount : base.extraShards, fragmentCount / 1e6,
              pass3dMs > 0 ? fragmentCount / (pass3dMs * 1e6) : 0.0, mib);
  if (method->PassNames().size() > 2) {  // the passes of a many-pass method, by name
    std::printf("%18s", "");
    for (size_t i = 0; i < m.passes.size(); ++i)
      std::printf(" %s %.3f", method->PassNames()[i].c_str(), Median(m.passes[i]));
    std::printf("\n");
  }
}

int RunBench(rhi::Device* device, rhi::DeviceContext* ctx, const Options& o) {
  if (o.scene != "demo" && o.scene != "paper" && o.scene != "heavy" && o.scene != "complexity")
    Fail("--scene takes demo, paper, heavy or complexity");
  const int frames = o.frames > 0 ? o.frames : 60;
  std::printf("replay --bench --scene %s on %s, %d timed frames (medians)\n", o.scene.c_str(),
              device->GetAdapterName(), frames);
  for (const BenchCase& bc : BenchCases(o)) {
    renderer::TranslucencySettings base = bc.settings;
    base.fragmentStorage = o.fragmentStorage;
    base.msaaSamples = o.msaaSamples;
    base.timestamps = true;
    base.countParticles = false;
    const bool particles = base.scene == "smoke" || base.scene == "fire";
    // Warm-up: the updates the smoke needs to reach its steady state (the longest life).
    const int warmup = o.warmup >= 0 ? std::max(1, o.warmup)
                                     : particles ? int(base.rule.minLife + base.rule.lifeRange) : 2;
    std::printf("\n%s: %ux%u, %s%s, %d warm-up frames, the methods' frames interleaved\n", bc.name.c_str(),
                base.width, base.height, base.scene.c_str(), base.extraShards ? " + shards" : "", warmup);
    std::printf("%-20s %9s %9s %9s %9s %9s %9s %9s %9s %9s %10s %9s %9s %10s\n", "method", "FPS(GPU)", "GPU ms",
                "opaque", "update", "3D pass", "later", "CPU ms", "wall ms", "particles", "shards", "3D Mfrag",
                "Gfrag/s", "MiB");
    // One replay per method, each warmed up; then frame i of every method in turn, so that
    // all methods see the same load on a shared machine (lavapipe's cores) over the run.
    std::vector<BenchReplay> replays =
        WarmedUpReplays(device, ctx, base, warmup, o.benchMethods.empty() ? renderer::oit::Methods() : o.benchMethods);
    for (int i = 0; i < frames; ++i)
      for (BenchReplay& r : replays) TimeFrame(*r.replay, *r.method, r.samples);
    std::map<std::string, double> gpuMs, cpuMs, translucentMs;
    for (BenchReplay& r : replays) {
      gpuMs[r.method->name] = Median(r.samples.gpu), cpuMs[r.method->name] = Median(r.samples.cpu);
      translucentMs[r.method->name] = Median(r.samples.methodPasses);
      PrintBenchRow(r, base, particles);
    }
    if (gpuMs.count("alpha") && gpuMs.count("wboit"))
      std::printf("%s: WBOIT/alpha GPU frame-time ratio %.3f (target <= 1.27; paper, smoke on D3D11: "
                  "1.183/0.935 = 1.265); CPU ms per frame: alpha %.3f, WBOIT %.3f\n",
                  bc.name.c_str(), gpuMs["wboit"] / gpuMs["alpha"], cpuMs["alpha"], cpuMs["wboit"]);
    // Issue 19: all the passes of the compute-tile methods against alpha's one.
    for (const char* compute : {"compute-sorted", "compute-wboit"})
      if (translucentMs.count(compute) && translucentMs.count("alpha") && translucentMs["alpha"] > 0)
        std::printf("%s: %s translucent passes %.3f ms, alpha's %.3f ms: ratio %.3f (target <= 0.5 in the paper "
                    "scene); FPS(GPU) %.0f (paper: 1070)\n",
                    bc.name.c_str(), compute, translucentMs[compute], translucentMs["alpha"],
                    translucentMs[compute] / translucentMs["alpha"], 1000.0 / gpuMs[compute]);
  }
  return 0;
}

int RunCompare(rhi::Device* device, rhi::DeviceContext* ctx, const Options& o, const std::string& command) {
  CompareRun run;
  run.adapter = device->GetAdapterName();
  run.command = command;
  run.settings.width = o.width, run.settings.height = o.height;
  if (o.frames > 0) run.settings.timedFrames = o.frames;
  if (o.peelLayersGiven) run.settings.maxLayers = o.peelLayers;
  std::vector<renderer::SceneComparison> scenes;
  std::string error;
  auto progress = [](const renderer::SceneInfo& scene, const MethodInfo& method) {
    std::printf("compare: %s / %s\n", scene.name, method.name);
    std::fflush(stdout);
  };
  if (!renderer::CompareMethods(device, ctx, run.settings, &scenes, &error, progress)) Fail(error);
  MakeOutFolder(o.out);
  const std::filesystem::path out(o.out);
  if (!WriteComparisonMarkdown((out / "comparison.md").string(), run, scenes, &error) ||
      !WriteCompareGrid((out / "compare_grid.png").string(), run, scenes, &error) ||
      !WriteParetoPlots(o.out, scenes, &error))
    Fail(error);
  std::printf("%-12s %-28s %9s %8s %7s %8s %10s %9s\n", "scene", "method", "RMSE", "PSNR", "SSIM", ">2/255",
              "bytes/px", "GPU ms");
  for (const renderer::SceneComparison& scene : scenes)
    for (const renderer::MethodResult& r : scene.methods) {
      if (r.refused) {
        std::printf("%-12s %-28s refused: %s\n", scene.scene->name, r.method->name, r.reason.c_str());
        continue;
      }
      std::printf("%-12s %-28s %9.3f %8.2f %7.4f %7.2f%% %10.1f %9.3f%s\n", scene.scene->name, r.method->name, r.rmse,
                  r.psnr, r.ssim, 100.0 * r.shareOff, r.bytesPerPixel, r.gpuMs,
                  r.method == scene.reference ? "  (reference)" : "");
    }
  std::printf("wrote %s, %s and the Pareto plots\n", (out / "comparison.md").c_str(), (out / "compare_grid.png").c_str());
  return 0;
}

}  // namespace

// Bounds of the counts the options take.
constexpr int64_t kMaxFrames = 1000000;
constexpr int64_t kMaxLayers = 64;

int main(int argc, char** argv) {
  if (ReplayWindowRequested(argc, argv)) return RunReplayWindow(argc, argv);  // replay --window: app/replay_window.cpp
  Options o;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) Fail("missing value after " + a);
      return argv[++i];
    };
    if (a == "--demo") {
      o.demo = next();
      if (!renderer::FindScene(o.demo)) Fail("--demo takes a scene: " + renderer::SceneNames());
    } else if (a == "--method") {
      o.method = renderer::oit::FindMethod(next());
      if (!o.method) Fail("--method takes a method: " + renderer::oit::MethodNames());
    } else if (a == "--methods") {
      std::stringstream list(next());
      for (std::string name; std::getline(list, name, ',');) {
        const MethodInfo* m = renderer::oit::FindMethod(name);
        if (!m) Fail("--methods takes methods separated by commas: " + renderer::oit::MethodNames());
        o.benchMethods.push_back(m);
      }
    } else if (a == "--list-methods") {
      o.listMethods = true;
    } else if (a == "--list-scenes") {
      o.listScenes = true;
    } else if (a == "--frames") {
      o.frames = static_cast<int>(IntegerOption(a, next(), 1, kMaxFrames));
    } else if (a == "--size") {
      SizeOption(next(), &o.width, &o.height);
    } else if (a == "--out") {
      o.out = next();
    } else if (a == "--figures") {
      o.figures = true;
    } else if (a == "--compare") {
      o.compare = true;
    } else if (a == "--document") {
      o.document = next();
      if (o.document != "001" && o.document != "003")
        Fail("--document takes 001 or 003 (the figures of one document alone)");
    } else if (a == "--bench") {
      o.bench = true;
    } else if (a == "--scene") {
      o.scene = next();
    } else if (a == "--warmup") {
      o.warmup = static_cast<int>(IntegerOption(a, next(), 0, kMaxFrames));
    } else if (a == "--all-frames") {
      o.allFrames = true;
    } else if (a == "--peel-layers") {
      o.peelLayers = static_cast<uint32_t>(IntegerOption(a, next(), 1, kMaxLayers));
      o.peelLayersGiven = true;
    } else if (a == "--fragment-sizing") {
      const std::string v = next();
      if (v != "exact" && v != "late" && v != "redraw") Fail("--fragment-sizing takes exact, late or redraw");
      o.fragmentStorage.sizing = v == "exact" ? renderer::oit::FragmentSizing::Exact
                                 : v == "late" ? renderer::oit::FragmentSizing::Late
                                               : renderer::oit::FragmentSizing::GrowAndRedraw;
    } else if (a == "--min-depth-slope") {
      // m per scene unit of view depth (document 003 sweeps 1 to 200)
      std::string error;
      const std::optional<double> m = cli::ParseNumber(a, next(), 1e-3, 1e6, &error);
      if (!m) Fail(error);
      o.minDepthSlope = float(*m);
    } else if (a == "--msaa") {
      o.msaaSamples = static_cast<uint32_t>(IntegerOption(a, next(), 4, 8));
      if (o.msaaSamples != 4 && o.msaaSamples != 8) Fail("--msaa takes 4 or 8 (samples per pixel)");
    } else if (a == "--layer") {
      o.layer = static_cast<int>(IntegerOption(a, next(), 0, kMaxLayers - 1));  // 0: the nearest
    } else {
      Fail("unknown argument " + a +
           "\nusage: replay --demo SCENE --method METHOD [--frames N] [--size WxH] [--peel-layers N] [--layer K]"
           " [--fragment-sizing exact|late|redraw] [--min-depth-slope M] [--msaa 4|8] --out DIR"
           "\n       replay --list-methods | --list-scenes"
           "\n       replay --figures [--document 001|003] --out DIR\n       replay --compare [--size WxH] [--out DIR] [--frames N] [--peel-layers N]\n       replay --bench [--scene demo|paper|heavy|complexity] [--frames N] [--warmup N] [--methods A,B,...]"
           "\n  scenes: " + renderer::SceneNames() + "\n  methods: " + renderer::oit::MethodNames());
    }
  }
  if (o.listMethods) return ListMethods();
  if (o.listScenes) return ListScenes();
  rhi::DEVICE_OPTIONS options;
  options.OnMessage = [](rhi::MESSAGE_CATEGORY, rhi::MESSAGE_SEVERITY severity, const char* text) {
    const bool error = severity <= rhi::MESSAGE_SEVERITY_ERROR;
    if (error) ++gErrors;
    std::fprintf(stderr, "%s: %s\n", error ? "error" : "message", text);
  };
  rhi::ComPtr<rhi::Device> device;
  rhi::ComPtr<rhi::DeviceContext> ctx;
  if (rhi::FAILED(rhi::CreateDevice(&options, device.GetAddressOf(), ctx.GetAddressOf())))
    Fail("CreateDevice failed (is a Vulkan driver, e.g. mesa-vulkan-drivers, installed?)");
  std::string command = "replay";
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
  int rc = o.compare ? RunCompare(device.Get(), ctx.Get(), o, command)
           : o.bench ? RunBench(device.Get(), ctx.Get(), o)
           : o.figures ? RunFigures(device.Get(), ctx.Get(), o)
                       : RunOne(device.Get(), ctx.Get(), o);
  if (gErrors > 0) Fail(std::to_string(gErrors) + " RHI error message(s) (see above)");
  return rc;
}
