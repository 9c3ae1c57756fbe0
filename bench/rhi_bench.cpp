// rhi_bench: CPU cost per draw through the RHI against the same command stream
// recorded with raw Vulkan calls, in one binary, on the same physical device.
//
// Each iteration of BM_RhiVsRaw records one RHI batch and one raw batch of
// kDrawsPerBatch draws each (see bench_scene.h for the stream). Only the
// recordings are timed (manual time = the RHI's): the submissions and the waits
// for the GPU run outside the measured intervals. For the RHI, the measured
// interval is everything from the first binding call of the batch to the last
// Draw: state tracking, pipeline-cache lookups, barriers, dynamic rendering
// begin, push descriptors, vkCmd* recording (and command-buffer acquisition if
// the backend does it lazily there). Flush (end rendering, end command buffer,
// vkQueueSubmit2) and the wait are excluded, as the raw side's end, submit,
// wait and command-pool reset are.
//
// The clock is the recording thread's CPU time (CLOCK_THREAD_CPUTIME_ID): on a
// shared machine the wall clock also counts the time the thread waits for a
// core, which is not a cost of the RHI. Both clocks are reported.
//
// Counters: rhi_ns_per_draw / raw_ns_per_draw = recorded thread-CPU nanoseconds
// / draws; *_wall_ns_per_draw = the same intervals on the wall clock; ratio =
// RHI / raw over the repetition. After the run the binary prints the median of
// the ratios over the repetitions (--benchmark_repetitions=N), with their range.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench_scene.h"
#include "raw_vulkan.h"
#include "rhi/rhi.h"

namespace bench {
namespace {

using rhi::ComPtr;
using Clock = std::chrono::steady_clock;

double ThreadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

// ---------------------------------------------------------------------------
// The RHI side

class RhiScene {
 public:
  explicit RhiScene(const SceneShaders& shaders) {
    rhi::DEVICE_OPTIONS options;
    options.EnableValidation = rhi::FALSE;  // and RHI_VALIDATION must not be set for timing runs
    options.OnMessage = [this](rhi::MESSAGE_CATEGORY, rhi::MESSAGE_SEVERITY severity, const char* text) {
      if (severity <= rhi::MESSAGE_SEVERITY_WARNING) {
        if (errors_.size() < 8) errors_.push_back(text);
        ++errorCount_;
      }
    };
    if (rhi::CreateDevice(&options, device_.GetAddressOf(), context_.GetAddressOf()) != rhi::S_OK) {
      std::fprintf(stderr, "rhi_bench: rhi::CreateDevice failed\n");
      for (const auto& e : errors_) std::fprintf(stderr, "  %s\n", e.c_str());
      std::exit(4);
    }
    auto ok = [&](rhi::HRESULT hr, const char* what) {
      if (hr == rhi::S_OK) return;
      std::fprintf(stderr, "rhi_bench: %s failed (0x%08x)\n", what, static_cast<unsigned>(hr));
      for (const auto& e : errors_) std::fprintf(stderr, "  %s\n", e.c_str());
      std::exit(4);
    };

    rhi::TEXTURE2D_DESC targetDesc{};
    targetDesc.Width = targetDesc.Height = kTargetSize;
    targetDesc.MipLevels = targetDesc.ArraySize = 1;
    targetDesc.Format = rhi::DXGI_FORMAT_R8G8B8A8_UNORM;
    targetDesc.SampleDesc.Count = 1;
    targetDesc.Usage = rhi::USAGE_DEFAULT;
    targetDesc.BindFlags = rhi::BIND_RENDER_TARGET;
    ok(device_->CreateTexture2D(&targetDesc, nullptr, target_.GetAddressOf()), "CreateTexture2D");
    ok(device_->CreateRenderTargetView(target_.Get(), nullptr, rtv_.GetAddressOf()), "CreateRenderTargetView");

    for (int i = 0; i < 2; ++i) {
      ok(device_->CreateVertexShader(shaders.vs[i].data(), shaders.vs[i].size() * 4, nullptr, vs_[i].GetAddressOf()),
         "CreateVertexShader");
      ok(device_->CreatePixelShader(shaders.ps[i].data(), shaders.ps[i].size() * 4, nullptr, ps_[i].GetAddressOf()),
         "CreatePixelShader");
    }
    const rhi::INPUT_ELEMENT_DESC position{"POSITION", 0, rhi::DXGI_FORMAT_R32G32_FLOAT, 0, 0,
                                           rhi::INPUT_PER_VERTEX_DATA, 0};
    ok(device_->CreateInputLayout(&position, 1, shaders.vs[0].data(), shaders.vs[0].size() * 4,
                                  inputLayout_.GetAddressOf()),
       "CreateInputLayout");

    // Blend 0: opaque (D3D11 default). Blend 1: blend by the blend factor.
    rhi::BLEND_DESC opaque{};
    rhi::BLEND_DESC byFactor{};
    auto& rt = byFactor.RenderTarget[0];
    rt.BlendEnable = rhi::TRUE;
    rt.SrcBlend = rt.SrcBlendAlpha = rhi::BLEND_BLEND_FACTOR;
    rt.DestBlend = rt.DestBlendAlpha = rhi::BLEND_INV_BLEND_FACTOR;
    ok(device_->CreateBlendState(&opaque, blend_[0].GetAddressOf()), "CreateBlendState");
    ok(device_->CreateBlendState(&byFactor, blend_[1].GetAddressOf()), "CreateBlendState");
    // Depth-stencil 0: depth off. 1: depth + stencil on. Different serials, so they
    // enter the pipeline key (no DSV is bound, so both build the same Vulkan state).
    rhi::DEPTH_STENCIL_DESC depthOff{};
    depthOff.DepthEnable = rhi::FALSE;
    rhi::DEPTH_STENCIL_DESC depthOn{};
    depthOn.DepthFunc = rhi::COMPARISON_LESS_EQUAL;
    depthOn.StencilEnable = rhi::TRUE;
    ok(device_->CreateDepthStencilState(&depthOff, depth_[0].GetAddressOf()), "CreateDepthStencilState");
    ok(device_->CreateDepthStencilState(&depthOn, depth_[1].GetAddressOf()), "CreateDepthStencilState");

    for (int i = 0; i < 2; ++i) {
      rhi::BUFFER_DESC vbDesc{sizeof kTriangles[i], rhi::USAGE_DEFAULT, rhi::BIND_VERTEX_BUFFER, 0, 0, 0};
      rhi::SUBRESOURCE_DATA vbData{kTriangles[i], 0, 0};
      ok(device_->CreateBuffer(&vbDesc, &vbData, vb_[i].GetAddressOf()), "CreateBuffer (vertex)");
      rhi::BUFFER_DESC cbDesc{sizeof(DrawConstants), rhi::USAGE_DEFAULT, rhi::BIND_CONSTANT_BUFFER, 0, 0, 0};
      rhi::SUBRESOURCE_DATA cbData{&kConstants[i], 0, 0};
      ok(device_->CreateBuffer(&cbDesc, &cbData, cb_[i].GetAddressOf()), "CreateBuffer (constant)");
    }
    rhi::BUFFER_DESC readbackDesc{sizeof(DrawConstants), rhi::USAGE_STAGING, 0, rhi::CPU_ACCESS_READ, 0, 0};
    ok(device_->CreateBuffer(&readbackDesc, nullptr, readback_.GetAddressOf()), "CreateBuffer (staging)");
  }

  ~RhiScene() {
    if (context_) {
      context_->ClearState();
      context_->Flush();
    }
  }

  std::string AdapterName() { return device_->GetAdapterName(); }
  size_t ErrorCount() const { return errorCount_; }
  const std::vector<std::string>& Errors() const { return errors_; }

  // The timed part: the D3D11-style stream of one batch. Not inlined, so a
  // profiler can collect exactly the timed batches (callgrind --toggle-collect).
  [[gnu::noinline]] void RecordBatch(int draws) { Record(draws); }

  // Builds the 4 pipelines (and everything else lazy) outside RecordBatch.
  void Warmup() {
    Record(kDrawsPerBatch);
    SubmitAndWait();
  }

  // The untimed part: Flush, then a blocking wait for the GPU. D3D11 has no
  // "wait idle"; mapping a staging copy for reading blocks on the fence
  // (vkWaitForFences) without spinning against the driver's threads, which
  // polling an event query would do on a machine with few cores.
  void SubmitAndWait() {
    rhi::DeviceContext* ctx = context_.Get();
    ctx->CopyResource(readback_.Get(), cb_[0].Get());
    rhi::MAPPED_SUBRESOURCE mapped{};
    if (ctx->Map(readback_.Get(), 0, rhi::MAP_READ, 0, &mapped) == rhi::S_OK) ctx->Unmap(readback_.Get(), 0);
  }

 private:
  void Record(int draws) {
    rhi::DeviceContext* ctx = context_.Get();
    rhi::RenderTargetView* rtv = rtv_.Get();
    ctx->OMSetRenderTargets(1, &rtv, nullptr);
    const rhi::VIEWPORT viewport{0, 0, static_cast<float>(kTargetSize), static_cast<float>(kTargetSize), 0, 1};
    ctx->RSSetViewports(1, &viewport);
    ctx->IASetInputLayout(inputLayout_.Get());
    ctx->IASetPrimitiveTopology(rhi::PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    for (int i = 0; i < draws; ++i) {
      const DrawChoice c = ChoiceFor(i);
      ctx->OMSetBlendState(blend_[c.blend].Get(), kBlendFactors[c.blend], rhi::DEFAULT_SAMPLE_MASK);
      ctx->OMSetDepthStencilState(depth_[c.pair].Get(), kStencilRefs[c.pair]);
      ctx->VSSetShader(vs_[c.pair].Get(), nullptr, 0);
      ctx->PSSetShader(ps_[c.pair].Get(), nullptr, 0);
      rhi::Buffer* vb = vb_[c.vb].Get();
      const rhi::UINT stride = kVertexStride, offset = 0;
      ctx->IASetVertexBuffers(0, 1, &vb, &stride, &offset);
      rhi::Buffer* cb = cb_[c.cb].Get();
      ctx->VSSetConstantBuffers(0, 1, &cb);
      ctx->Draw(3, 0);
    }
  }

  ComPtr<rhi::Device> device_;
  ComPtr<rhi::DeviceContext> context_;
  ComPtr<rhi::Texture2D> target_;
  ComPtr<rhi::RenderTargetView> rtv_;
  ComPtr<rhi::VertexShader> vs_[2];
  ComPtr<rhi::PixelShader> ps_[2];
  ComPtr<rhi::InputLayout> inputLayout_;
  ComPtr<rhi::BlendState> blend_[2];
  ComPtr<rhi::DepthStencilState> depth_[2];
  ComPtr<rhi::Buffer> vb_[2];
  ComPtr<rhi::Buffer> cb_[2];
  ComPtr<rhi::Buffer> readback_;
  std::vector<std::string> errors_;
  size_t errorCount_ = 0;
};

// ---------------------------------------------------------------------------
// Scenes, created on first use (outside the timed loop) and destroyed by main.

const SceneShaders& Shaders() {
  static const SceneShaders shaders = CompileSceneShaders();
  return shaders;
}

std::unique_ptr<RhiScene> gRhi;
std::unique_ptr<RawVulkan> gRaw;

RhiScene& Rhi() {
  if (!gRhi) {
    gRhi = std::make_unique<RhiScene>(Shaders());
    // Warm-up: builds the 4 pipelines so the timed batches only hit the cache.
    gRhi->Warmup();
  }
  return *gRhi;
}

RawVulkan& Raw() {
  if (!gRaw) {
    gRaw = std::make_unique<RawVulkan>(Shaders());
    gRaw->Warmup();
  }
  return *gRaw;
}

// One timed recording: thread CPU seconds and wall seconds of `record`.
struct Timed {
  double cpuSeconds = 0;
  double wallSeconds = 0;

  Timed& operator+=(const Timed& other) {
    cpuSeconds += other.cpuSeconds;
    wallSeconds += other.wallSeconds;
    return *this;
  }
};
template <class Record>
Timed TimeRecording(Record&& record) {
  const Clock::time_point wallStart = Clock::now();
  const double cpuStart = ThreadCpuSeconds();
  record();
  const double cpuSeconds = ThreadCpuSeconds() - cpuStart;
  return {cpuSeconds, std::chrono::duration<double>(Clock::now() - wallStart).count()};
}

// The headline: each iteration records one RHI batch and one raw batch, each
// followed by its untimed submit-and-wait, so both halves are timed under the
// same machine load and the same state of the process heap, in which
// lavapipe allocates every recorded command. (Timed one after the other, a
// repetition of either half could land in a slower state of that heap than
// the other half's, and the ratio moved by up to 1.6x between runs.) The
// manual time is the RHI's; the ratio counter is RHI / raw over the repetition.
void BM_RhiVsRaw(benchmark::State& state) {
  RhiScene& rhi = Rhi();
  RawVulkan& raw = Raw();
  Timed rhiTotal, rawTotal;
  int64_t draws = 0;
  for (auto _ : state) {
    const Timed rhiBatch = TimeRecording([&] { rhi.RecordBatch(kDrawsPerBatch); });
    rhi.SubmitAndWait();
    const Timed rawBatch = TimeRecording([&] { raw.RecordBatch(kDrawsPerBatch, false); });
    raw.SubmitAndWait();
    state.SetIterationTime(rhiBatch.cpuSeconds);
    rhiTotal += rhiBatch;
    rawTotal += rawBatch;
    draws += kDrawsPerBatch;
  }
  state.SetItemsProcessed(draws);
  const double nsPerDraw = draws ? 1e9 / static_cast<double>(draws) : 0.0;
  state.counters["rhi_ns_per_draw"] = rhiTotal.cpuSeconds * nsPerDraw;
  state.counters["raw_ns_per_draw"] = rawTotal.cpuSeconds * nsPerDraw;
  state.counters["rhi_wall_ns_per_draw"] = rhiTotal.wallSeconds * nsPerDraw;
  state.counters["raw_wall_ns_per_draw"] = rawTotal.wallSeconds * nsPerDraw;
  state.counters["ratio"] = rawTotal.cpuSeconds > 0 ? rhiTotal.cpuSeconds / rawTotal.cpuSeconds : 0.0;
  // A refused draw would make the RHI look cheap: any error or warning fails the benchmark.
  if (rhi.ErrorCount() != 0) state.SkipWithError(("the RHI reported: " + rhi.Errors().front()).c_str());
}

// Diagnostic, not the baseline: raw Vulkan that re-sets viewport, scissor,
// topology and primitive restart after every pipeline bind, as the RHI did before 538b266.
void BM_RawVulkanDrawReemit(benchmark::State& state) {
  RawVulkan& raw = Raw();
  double cpuSeconds = 0;
  int64_t draws = 0;
  for (auto _ : state) {
    const Timed batch = TimeRecording([&] { raw.RecordBatch(kDrawsPerBatch, true); });
    raw.SubmitAndWait();
    state.SetIterationTime(batch.cpuSeconds);
    cpuSeconds += batch.cpuSeconds;
    draws += kDrawsPerBatch;
  }
  state.SetItemsProcessed(draws);
  state.counters["raw_ns_per_draw"] = draws ? cpuSeconds * 1e9 / static_cast<double>(draws) : 0.0;
}

BENCHMARK(BM_RhiVsRaw)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RawVulkanDrawReemit)->UseManualTime()->Unit(benchmark::kMicrosecond);

// ---------------------------------------------------------------------------
// Reporting: the console output, plus each counter's values per benchmark.

class CapturingReporter : public benchmark::ConsoleReporter {
 public:
  using ConsoleReporter::ConsoleReporter;

  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.error_occurred) continue;
      const bool median = run.run_type == Run::RT_Aggregate && run.aggregate_name == "median";
      if (run.run_type != Run::RT_Iteration && !median) continue;
      for (const auto& [counter, value] : run.counters) {
        const std::string key = run.run_name.function_name + "/" + counter;
        (median ? medians_[key] : samples_[key]).push_back(value.value);
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }

  // The median, minimum and maximum of a counter over the repetitions seen;
  // with --benchmark_report_aggregates_only only the median is known (min = max = median).
  struct Spread {
    double median = 0, min = 0, max = 0;
  };
  bool Counter(const std::string& benchmark, const std::string& counter, Spread* spread) const {
    const std::string key = benchmark + "/" + counter;
    const auto& values = samples_.contains(key) ? samples_ : medians_;
    auto it = values.find(key);
    if (it == values.end() || it->second.empty()) return false;
    std::vector<double> v = it->second;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    spread->median = n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
    spread->min = v.front();
    spread->max = v.back();
    return true;
  }

 private:
  std::map<std::string, std::vector<double>> samples_;  // per repetition
  std::map<std::string, std::vector<double>> medians_;  // the median aggregate
};

}  // namespace
}  // namespace bench

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::AddCustomContext("draws_per_batch", std::to_string(bench::kDrawsPerBatch));
  bench::CapturingReporter reporter(isatty(fileno(stdout)) ? benchmark::ConsoleReporter::OO_ColorTabular
                                                           : benchmark::ConsoleReporter::OO_Tabular);
  benchmark::RunSpecifiedBenchmarks(&reporter);

  using Spread = bench::CapturingReporter::Spread;
  Spread ratio, rhiNs, rawNs, reemitNs;
  if (reporter.Counter("BM_RhiVsRaw", "ratio", &ratio) && reporter.Counter("BM_RhiVsRaw", "rhi_ns_per_draw", &rhiNs) &&
      reporter.Counter("BM_RhiVsRaw", "raw_ns_per_draw", &rawNs)) {
    std::printf("RHI / raw per-draw CPU cost: %.2f (median of the repetitions' ratios, min %.2f, max %.2f; "
                "medians RHI %.0f ns, raw %.0f ns)\n",
                ratio.median, ratio.min, ratio.max, rhiNs.median, rawNs.median);
    if (reporter.Counter("BM_RawVulkanDrawReemit", "raw_ns_per_draw", &reemitNs))
      std::printf("  diagnostic: raw re-emitting dynamic state per pipeline bind: %.0f ns (RHI / that: %.2f)\n",
                  reemitNs.median, rhiNs.median / reemitNs.median);
  } else {
    std::printf("RHI / raw per-draw CPU cost: not available (run BM_RhiVsRaw)\n");
  }
  if (bench::gRhi || bench::gRaw)
    std::printf("Vulkan device: RHI \"%s\", raw \"%s\"\n", bench::gRhi ? bench::gRhi->AdapterName().c_str() : "-",
                bench::gRaw ? bench::gRaw->DeviceName().c_str() : "-");
  std::fflush(stdout);
  bench::gRhi.reset();
  bench::gRaw.reset();
  benchmark::Shutdown();
  return 0;
}
