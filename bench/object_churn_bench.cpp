// object_churn_bench: does memory stay flat while an application creates,
// uses and releases the same objects over and over?
//
// Two loops, each as an application that recreates its objects per frame:
//  - blend: CreateBlendState (one desc) -> bind -> Draw -> unbind -> Release;
//  - pixel shader: CreatePixelShader (one bytecode) -> bind -> Draw -> unbind -> Release.
// Unbinding lets each release destroy the object, so each creation makes a new
// one. Pipelines are keyed by the objects' contents (rhi/src/pipelines.h), so
// every new object should find the pipeline built for the first; keyed by
// object, each cycle would build and keep one more pipeline. Prints the
// resident set size (/proc/self/statm) after a warm-up and after each loop;
// a frame of 100 cycles ends with a wait for the GPU.
//
//   object_churn_bench [--blend-cycles N] [--shader-cycles N]
//
// The device is picked as everywhere else (RHI_DEVICE, else lavapipe).
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "cli_args.h"
#include "hlsl/hlsl_compiler.h"
#include "rhi/query_wait.h"
#include "rhi/rhi.h"

namespace {

using rhi::ComPtr;

constexpr const char* kVS = R"(float4 main(uint id : SV_VertexID) : SV_Position {
  return float4(float(id & 1) * 4 - 1, 1 - float(id & 2) * 2, 0.5, 1); })";
constexpr const char* kPS = R"(float4 main() : SV_Target { return float4(0.25, 0.5, 0.75, 0.5); })";

[[noreturn]] void Fail(const std::string& message) {
  std::fprintf(stderr, "object_churn_bench: %s\n", message.c_str());
  std::exit(2);
}

double ResidentMegabytes() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

std::vector<uint32_t> Compile(const char* source, const char* profile) {
  hlsl::CompileRequest request;
  request.source = source;
  request.fileName = "object_churn_bench.hlsl";
  request.entryPoint = "main";
  request.profile = profile;
  hlsl::CompileResult result = hlsl::CompileHlsl(request);
  if (!result.ok) Fail(result.FormatErrors());
  return result.spirv;
}

struct Options {
  int64_t blendCycles = 10000;
  int64_t shaderCycles = 3000;
};

Options ParseOptions(int argc, char** argv) {
  Options options;
  std::string error;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    int64_t* target = arg == "--blend-cycles" ? &options.blendCycles
                      : arg == "--shader-cycles" ? &options.shaderCycles
                                                 : nullptr;
    if (!target) Fail("unknown option '" + arg + "' (usage: [--blend-cycles N] [--shader-cycles N])");
    if (i + 1 >= argc) Fail(arg + " needs a value");
    std::optional<int64_t> value = cli::ParseInteger(arg, argv[++i], 1, 10000000, &error);
    if (!value) Fail(error);
    *target = *value;
  }
  return options;
}

class Churn {
 public:
  Churn() {
    rhi::DEVICE_OPTIONS options;
    options.OnMessage = [](rhi::MESSAGE_CATEGORY, rhi::MESSAGE_SEVERITY severity, const char* text) {
      if (severity <= rhi::MESSAGE_SEVERITY_WARNING) Fail(std::string("device message: ") + text);
    };
    if (rhi::CreateDevice(&options, device_.GetAddressOf(), context_.GetAddressOf()) != rhi::S_OK)
      Fail("rhi::CreateDevice failed");
    rhi::TEXTURE2D_DESC desc{16, 16, 1, 1, rhi::DXGI_FORMAT_R8G8B8A8_UNORM, {1, 0}, rhi::USAGE_DEFAULT,
                             rhi::BIND_RENDER_TARGET, 0, 0};
    Check(device_->CreateTexture2D(&desc, nullptr, target_.GetAddressOf()), "CreateTexture2D");
    Check(device_->CreateRenderTargetView(target_.Get(), nullptr, rtv_.GetAddressOf()), "CreateRenderTargetView");
    vsCode_ = Compile(kVS, "vs_5_0");
    psCode_ = Compile(kPS, "ps_5_0");
    Check(device_->CreateVertexShader(vsCode_.data(), vsCode_.size() * 4, nullptr, vs_.GetAddressOf()),
          "CreateVertexShader");
    Check(device_->CreatePixelShader(psCode_.data(), psCode_.size() * 4, nullptr, ps_.GetAddressOf()),
          "CreatePixelShader");
    context_->OMSetRenderTargets(1, rtv_.GetAddressOf(), nullptr);
    rhi::VIEWPORT viewport{0, 0, 16, 16, 0, 1};
    context_->RSSetViewports(1, &viewport);
    context_->IASetPrimitiveTopology(rhi::PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    context_->VSSetShader(vs_.Get(), nullptr, 0);
    context_->PSSetShader(ps_.Get(), nullptr, 0);
  }

  const char* AdapterName() { return device_->GetAdapterName(); }

  void BlendCycle() {
    rhi::BLEND_DESC desc;
    desc.RenderTarget[0].BlendEnable = rhi::TRUE;
    desc.RenderTarget[0].SrcBlend = rhi::BLEND_SRC_ALPHA;
    desc.RenderTarget[0].DestBlend = rhi::BLEND_INV_SRC_ALPHA;
    ComPtr<rhi::BlendState> blend;
    Check(device_->CreateBlendState(&desc, blend.GetAddressOf()), "CreateBlendState");
    context_->OMSetBlendState(blend.Get(), nullptr, rhi::DEFAULT_SAMPLE_MASK);
    context_->Draw(3, 0);
    context_->OMSetBlendState(nullptr, nullptr, rhi::DEFAULT_SAMPLE_MASK);
  }

  void ShaderCycle() {
    ComPtr<rhi::PixelShader> ps;
    Check(device_->CreatePixelShader(psCode_.data(), psCode_.size() * 4, nullptr, ps.GetAddressOf()),
          "CreatePixelShader");
    context_->PSSetShader(ps.Get(), nullptr, 0);
    context_->Draw(3, 0);
    context_->PSSetShader(ps_.Get(), nullptr, 0);
  }

  // Ends a frame and waits for the GPU to finish it, so that what the RSS
  // shows is what the device keeps, not a queue of frames the (software) GPU
  // has yet to run.
  void EndFrame() {
    rhi::QUERY_DESC desc{rhi::QUERY_EVENT, 0};
    ComPtr<rhi::Query> event;
    Check(device_->CreateQuery(&desc, event.GetAddressOf()), "CreateQuery");
    context_->End(event.Get());
    rhi::BOOL done = rhi::FALSE;
    Check(rhi::WaitForData(context_.Get(), event.Get(), &done), "GetData");
  }

 private:
  static void Check(rhi::HRESULT hr, const char* what) {
    if (hr != rhi::S_OK) Fail(std::string(what) + " failed");
  }

  ComPtr<rhi::Device> device_;
  ComPtr<rhi::DeviceContext> context_;
  ComPtr<rhi::Texture2D> target_;
  ComPtr<rhi::RenderTargetView> rtv_;
  std::vector<uint32_t> vsCode_, psCode_;
  ComPtr<rhi::VertexShader> vs_;
  ComPtr<rhi::PixelShader> ps_;
};

template <class Cycle>
void Measure(const char* name, int64_t cycles, Churn& churn, Cycle cycle) {
  for (int i = 0; i < 10; ++i) cycle();  // warm-up: the first pipeline and allocator pools
  churn.EndFrame();
  const double before = ResidentMegabytes();
  for (int64_t i = 1; i <= cycles; ++i) {
    cycle();
    if (i % 100 == 0) churn.EndFrame();
  }
  churn.EndFrame();
  const double after = ResidentMegabytes();
  std::printf("%s: %lld cycles, RSS %.1f MB -> %.1f MB, %.2f KB per cycle\n", name, static_cast<long long>(cycles),
              before, after, (after - before) * 1024.0 / static_cast<double>(cycles));
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = ParseOptions(argc, argv);
  Churn churn;
  std::printf("device: %s\n", churn.AdapterName());
  Measure("create blend state -> draw -> release", options.blendCycles, churn, [&] { churn.BlendCycle(); });
  Measure("create pixel shader -> draw -> release", options.shaderCycles, churn, [&] { churn.ShaderCycle(); });
  return 0;
}
