// replay: the translucency demos of document 000 (SPEC.md), headless and deterministic.
//
//   replay --demo smoke|fire|shards --method alpha|wboit|colored|sorted [--frames N] [--size WxH] --out DIR
//       renders frames 0..N-1 (fixed time step, seeded, camera a function of the frame index)
//       and writes DIR/<demo>_<method>_<frame>.png for the last frame
//       (--all-frames: every frame; --literal-table4: colored composes with Table 4 as printed).
//       fire: flames drawn with additive blending for alpha and sorted (order-independent).
//   replay --figures --out DIR [--size WxH] [--frames N]
//       fig1_smoke_alpha_wboit.png (alpha | WBOIT), fig_shards_wboit_colored_sorted.png
//       (WBOIT | colored | sorted), fig_fire_additive_wboit_colored.png and per-method
//       RMSE / PSNR against the sorted reference
//   replay --bench [--scene demo|paper|heavy] [--frames N] [--warmup N] [--size WxH]
//       per method: FPS and frame ms from the GPU (TIMESTAMP queries inside a
//       TIMESTAMP_DISJOINT query, median over N frames), per-pass GPU ms, CPU ms per frame
//       (RenderFrame's recording and submission, median), wall ms; WBOIT/alpha ratio.
//       demo:  the smoke and shards demos at --size (default 640x360);
//       paper: 1280x720, smoke of a few thousand particles over the opaque scene (Fig. 2);
//       heavy: 1920x1080, 1M particles plus 10k instanced shards in one frame.
//       --warmup defaults to the updates the smoke needs to reach its steady state.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "renderer/translucency.h"
#include "replay_window.h"
#include "rhi/rhi.h"

using renderer::TranslucencyDemo;
using renderer::TranslucencyMethod;

namespace {

int gErrors = 0;

[[noreturn]] void Fail(const std::string& what) {
  std::fprintf(stderr, "replay: %s\n", what.c_str());
  std::exit(1);
}

struct Options {
  TranslucencyDemo demo = TranslucencyDemo::Smoke;
  TranslucencyMethod method = TranslucencyMethod::Wboit;
  int frames = -1;
  uint32_t width = 640, height = 360;
  std::string out = "out/replay";
  bool figures = false, bench = false, allFrames = false, literalTable4 = false;
  std::string scene = "demo";  // --bench: demo | paper | heavy
  int warmup = -1;
};

std::unique_ptr<renderer::Translucency> Make(rhi::Device* device, rhi::DeviceContext* ctx,
                                             renderer::TranslucencySettings settings) {
  std::string error;
  auto t = renderer::Translucency::Create(device, ctx, settings, &error);
  if (!t) Fail(error);
  return t;
}

int DefaultFrames(TranslucencyDemo demo) { return demo == TranslucencyDemo::Shards ? 1 : 120; }

// Renders frames 0..frames-1 with one method and returns the last frame.
std::vector<uint8_t> Replay(rhi::Device* device, rhi::DeviceContext* ctx, const renderer::TranslucencySettings& s,
                            TranslucencyMethod method, int frames) {
  auto t = Make(device, ctx, s);
  for (int i = 0; i < frames; ++i) t->RenderFrame(method);
  return t->ReadFrame();
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
  renderer::TranslucencySettings s;
  s.demo = o.demo;
  s.width = o.width, s.height = o.height;
  s.literalTable4 = o.literalTable4;
  const int frames = o.frames > 0 ? o.frames : DefaultFrames(o.demo);
  auto t = Make(device, ctx, s);
  std::filesystem::create_directories(o.out);
  for (int i = 0; i < frames; ++i) {
    t->RenderFrame(o.method);
    if (o.allFrames || i == frames - 1) {
      char name[256];
      std::snprintf(name, sizeof name, "%s_%s_%04d.png", renderer::ToString(o.demo), renderer::ToString(o.method), i);
      WritePng((std::filesystem::path(o.out) / name).string(), t->ReadFrame(), o.width, o.height);
    }
  }
  return 0;
}

int RunFigures(rhi::Device* device, rhi::DeviceContext* ctx, const Options& o) {
  std::filesystem::create_directories(o.out);
  const TranslucencyMethod methods[4] = {TranslucencyMethod::Alpha, TranslucencyMethod::Wboit,
                                         TranslucencyMethod::Colored, TranslucencyMethod::Sorted};
  std::printf("%-8s %-8s %10s %10s\n", "demo", "method", "RMSE", "PSNR dB");
  for (TranslucencyDemo demo : {TranslucencyDemo::Smoke, TranslucencyDemo::Fire, TranslucencyDemo::Shards}) {
    renderer::TranslucencySettings s;
    s.demo = demo;
    s.width = o.width, s.height = o.height;
    const int frames = o.frames > 0 ? o.frames : DefaultFrames(demo);
    std::vector<uint8_t> images[4];
    for (int i = 0; i < 4; ++i) images[i] = Replay(device, ctx, s, methods[i], frames);
    for (int i = 0; i < 4; ++i) {
      double rmse = renderer::Rmse(images[i], images[3]);
      std::printf("%-8s %-8s %10.3f %10.2f\n", renderer::ToString(demo), renderer::ToString(methods[i]), rmse,
                  renderer::Psnr(rmse));
    }
    uint32_t w = 0;
    if (demo == TranslucencyDemo::Smoke) {
      auto fig = SideBySide({images[0], images[1]}, o.width, o.height, &w);
      WritePng((std::filesystem::path(o.out) / "fig1_smoke_alpha_wboit.png").string(), fig, w, o.height);
      auto ref = SideBySide({images[1], images[2], images[3]}, o.width, o.height, &w);
      WritePng((std::filesystem::path(o.out) / "smoke_wboit_colored_sorted.png").string(), ref, w, o.height);
    } else if (demo == TranslucencyDemo::Fire) {
      auto fig = SideBySide({images[0], images[1], images[2]}, o.width, o.height, &w);
      WritePng((std::filesystem::path(o.out) / "fig_fire_additive_wboit_colored.png").string(), fig, w, o.height);
    } else {
      auto fig = SideBySide({images[1], images[2], images[3]}, o.width, o.height, &w);
      WritePng((std::filesystem::path(o.out) / "fig_shards_wboit_colored_sorted.png").string(), fig, w, o.height);
    }
  }
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
    s.demo = TranslucencyDemo::Smoke;
    s.width = 1280, s.height = 720;
    s.rule = {32, 2, 40, 60};  // steady state ~4,500 particles (the paper's demo: a few thousand)
    cases.push_back({"paper", s});
  } else if (o.scene == "heavy") {
    renderer::TranslucencySettings s;
    s.demo = TranslucencyDemo::Smoke;
    s.width = 1920, s.height = 1080;
    s.rule = {4096, 8, 20, 22};  // steady state ~1.0M particles (4096 * (1 + 8 * 30.5))
    s.particleSize = 0.05f;
    s.extraShards = 10000;
    cases.push_back({"heavy", s});
  } else {
    for (TranslucencyDemo demo : {TranslucencyDemo::Smoke, TranslucencyDemo::Shards}) {
      renderer::TranslucencySettings s;
      s.demo = demo;
      s.width = o.width, s.height = o.height;
      cases.push_back({renderer::ToString(demo), s});
    }
  }
  return cases;
}

// The timed samples of one method (medians are taken at the end).
struct MethodSamples {
  std::vector<double> wall, cpu, opaque, update, pass3d, compose, gpu, fragments;
};

// Renders and times one frame of `t`; the GPU times only when its timestamps came back.
void TimeFrame(renderer::Translucency& t, TranslucencyMethod method, MethodSamples& samples) {
  auto start = std::chrono::steady_clock::now();
  t.RenderFrame(method);
  auto recorded = std::chrono::steady_clock::now();
  renderer::PassTimes times = t.LastTimes();  // waits for the GPU
  auto done = std::chrono::steady_clock::now();
  samples.cpu.push_back(std::chrono::duration<double, std::milli>(recorded - start).count());
  samples.wall.push_back(std::chrono::duration<double, std::milli>(done - start).count());
  if (!times.valid) return;
  samples.opaque.push_back(times.opaqueMs), samples.update.push_back(times.updateMs);
  samples.pass3d.push_back(times.transparencyMs), samples.compose.push_back(times.composeMs);
  samples.gpu.push_back(times.totalMs), samples.fragments.push_back(double(times.transparencyFragments));
}

int RunBench(rhi::Device* device, rhi::DeviceContext* ctx, const Options& o) {
  if (o.scene != "demo" && o.scene != "paper" && o.scene != "heavy") Fail("--scene takes demo, paper or heavy");
  const int frames = o.frames > 0 ? o.frames : 60;
  std::printf("replay --bench --scene %s on %s, %d timed frames (medians)\n", o.scene.c_str(),
              device->GetAdapterName(), frames);
  constexpr TranslucencyMethod kMethods[4] = {TranslucencyMethod::Alpha, TranslucencyMethod::Wboit,
                                              TranslucencyMethod::Colored, TranslucencyMethod::Sorted};
  for (const BenchCase& bc : BenchCases(o)) {
    renderer::TranslucencySettings base = bc.settings;
    base.timestamps = true;
    base.countParticles = false;
    const bool particles = base.demo != TranslucencyDemo::Shards;
    // Warm-up: the updates the smoke needs to reach its steady state (the longest life).
    const int warmup = o.warmup >= 0 ? o.warmup : particles ? int(base.rule.minLife + base.rule.lifeRange) : 2;
    std::printf("\n%s: %ux%u, %s%s, %d warm-up frames, the methods' frames interleaved\n", bc.name.c_str(),
                base.width, base.height, renderer::ToString(base.demo), base.extraShards ? " + shards" : "", warmup);
    std::printf("%-8s %9s %9s %9s %9s %9s %9s %9s %9s %9s %10s %9s %9s\n", "method", "FPS(GPU)", "GPU ms", "opaque",
                "update", "3D pass", "compose", "CPU ms", "wall ms", "particles", "shards", "3D Mfrag", "Gfrag/s");
    // One replay per method, each warmed up; then frame i of every method in turn, so that
    // all methods see the same load on a shared machine (lavapipe's cores) over the run.
    std::unique_ptr<renderer::Translucency> replays[4];
    for (int mi = 0; mi < 4; ++mi) {
      replays[mi] = Make(device, ctx, base);
      for (int i = 0; i < warmup; ++i) {
        replays[mi]->RenderFrame(kMethods[mi]);
        replays[mi]->LastTimes();
      }
    }
    MethodSamples samples[4];
    for (int i = 0; i < frames; ++i)
      for (int mi = 0; mi < 4; ++mi) TimeFrame(*replays[mi], kMethods[mi], samples[mi]);
    double gpuMs[4] = {}, cpuMs[4] = {};
    for (int mi = 0; mi < 4; ++mi) {
      renderer::Translucency& t = *replays[mi];
      const MethodSamples& m = samples[mi];
      gpuMs[mi] = Median(m.gpu), cpuMs[mi] = Median(m.cpu);
      // The live count of the last frame (an extra SO_STATISTICS frame, not timed).
      uint64_t live = 0;
      if (particles) {
        t.RenderFrame(TranslucencyMethod::Sorted);  // the sorted method always counts
        live = t.particleCount();
        t.LastTimes();
      }
      // The 3D pass's fill rate: fragments shaded (and blended) per second.
      const double pass3dMs = Median(m.pass3d), fragmentCount = Median(m.fragments);
      std::printf("%-8s %9.1f %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %9llu %10u %9.2f %9.2f\n",
                  renderer::ToString(kMethods[mi]), gpuMs[mi] > 0 ? 1000.0 / gpuMs[mi] : 0.0, gpuMs[mi],
                  Median(m.opaque), Median(m.update), pass3dMs, Median(m.compose), cpuMs[mi], Median(m.wall),
                  static_cast<unsigned long long>(live),
                  base.demo == TranslucencyDemo::Shards ? base.shardCount : base.extraShards, fragmentCount / 1e6,
                  pass3dMs > 0 ? fragmentCount / (pass3dMs * 1e6) : 0.0);
    }
    std::printf("%s: WBOIT/alpha GPU frame-time ratio %.3f (target <= 1.27; paper, smoke on D3D11: "
                "1.183/0.935 = 1.265); CPU ms per frame: alpha %.3f, WBOIT %.3f\n",
                bc.name.c_str(), gpuMs[0] > 0 ? gpuMs[1] / gpuMs[0] : 0.0, cpuMs[0], cpuMs[1]);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (ReplayWindowRequested(argc, argv)) return RunReplayWindow(argc, argv);  // replay --window: app/replay_window.cpp
  Options o;
  bool haveMethod = false;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) Fail("missing value after " + a);
      return argv[++i];
    };
    if (a == "--demo") {
      if (!renderer::ParseDemo(next(), &o.demo)) Fail("--demo takes smoke, fire or shards");
    } else if (a == "--method") {
      if (!renderer::ParseMethod(next(), &o.method)) Fail("--method takes alpha, wboit, colored or sorted");
      haveMethod = true;
    } else if (a == "--frames") {
      o.frames = std::atoi(next().c_str());
    } else if (a == "--size") {
      std::string v = next();
      if (std::sscanf(v.c_str(), "%ux%u", &o.width, &o.height) != 2 || !o.width || !o.height)
        Fail("--size takes WxH");
    } else if (a == "--out") {
      o.out = next();
    } else if (a == "--figures") {
      o.figures = true;
    } else if (a == "--bench") {
      o.bench = true;
    } else if (a == "--scene") {
      o.scene = next();
    } else if (a == "--warmup") {
      o.warmup = std::atoi(next().c_str());
    } else if (a == "--all-frames") {
      o.allFrames = true;
    } else if (a == "--literal-table4") {
      o.literalTable4 = true;
    } else {
      Fail("unknown argument " + a +
           "\nusage: replay --demo smoke|fire|shards --method alpha|wboit|colored|sorted [--frames N] [--size WxH] --out DIR"
           "\n       replay --figures --out DIR\n       replay --bench [--scene demo|paper|heavy] [--frames N] [--warmup N]");
    }
  }
  (void)haveMethod;
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
  int rc = o.bench ? RunBench(device.Get(), ctx.Get(), o)
           : o.figures ? RunFigures(device.Get(), ctx.Get(), o)
                       : RunOne(device.Get(), ctx.Get(), o);
  if (gErrors > 0) Fail(std::to_string(gErrors) + " RHI error message(s) (see above)");
  return rc;
}
