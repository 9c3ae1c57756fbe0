// blend_fill_bench: what the output merger costs per blended render target on
// this device, apart from any demo's shaders.
//
// Document 000's Table 1 (WBOIT) blends every translucent fragment into two
// render targets and Table 3 (colored OIT) into three, where plain alpha
// blending writes one. How much that costs is a property of the device's
// raster back end, so this probe measures it with nothing else in the way: a
// pixel shader that writes small values into 1-3 targets, `--draws` layers of
// screen-covering tiles per measurement, ONE/ONE blending (or the named
// factors, or none). GPU time comes from TIMESTAMP queries inside a
// TIMESTAMP_DISJOINT query (the median of `--repeats` measurements per target
// set), the fragment count from an OCCLUSION query.
//
//   blend_fill_bench [--size WxH] [--draws N] [--repeats R] [--overlap L]
//                    [--jitter] [--gs] [--large] [--opacity] [--attributes] [--varying] [--depth]
//                    [--sampled]
//
// The options move the probe towards the smoke pass one property at a time
// (see Options). Use --opacity for figures that stand for real blending: without
// it, UNORM8 targets round the small values away and the blends leave them
// unchanged, which an NVIDIA H100 does several times faster (docs/PERF.md).
// The device is picked as everywhere else (RHI_DEVICE, else lavapipe).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "hlsl/hlsl_compiler.h"
#include "rhi/query_wait.h"
#include "rhi/rhi.h"

namespace {

using rhi::ComPtr;

constexpr const char* kHlsl = R"hlsl(
// Varying = 1 (--varying): outputs differ from pixel to pixel. Layers (--overlap):
// the screen is a 16x9 grid of tiles, each drawn Layers times in a row before
// the next, so consecutive primitives blend into the same pixels as overlapping
// particles do (1: every primitive covers new pixels). Jitter = 1 (--jitter):
// each quad moves by up to half a tile, so quads overlap at random offsets as
// billboards do. Scale (--large): SV_Target0's output is about 1000 instead of
// 1/1000, as WBOIT's weighted accum colours are (an RGBA16F sum then reaches infinity).
// Opacity = 1 (--opacity): every target gets alpha-like values, as the smoke's are.
cbuffer Probe : register(b0) {
  float Varying;
  uint Layers;
  float Jitter;
  float Scale;
  float Opacity;
};

// Clip-space corner of quad `quad` (tile quad / Layers), corner in [0, 1]^2.
float4 TileCorner(uint quad, float2 corner) {
  const uint2 grid = uint2(16, 9);
  uint tile = quad / Layers;
  float2 jitter = Jitter * (frac(float2(quad * 0.6180339, quad * 0.3819660)) - 0.5);
  float2 p = (float2(tile % grid.x, tile / grid.x) + corner + jitter) / float2(grid);
  return float4(p * float2(2, -2) + float2(-1, 1), 0, 1);
}

// ATTRIBUTES (--attributes): 12 more interpolated floats reach the pixel
// shader, as the billboard's uv, age and basis do; otherwise only the position.
struct QuadVertex {
  float4 position : SV_Position;
#ifdef ATTRIBUTES
  float4 extra0 : EXTRA0;
  float4 extra1 : EXTRA1;
  float4 extra2 : EXTRA2;
#endif
};

QuadVertex MakeQuadVertex(uint quad, float2 corner) {
  QuadVertex v;
  v.position = TileCorner(quad, corner);
#ifdef ATTRIBUTES
  v.extra0 = float4(corner, quad, 1);
  v.extra1 = v.position.yxzw;
  v.extra2 = float4(corner.yx, 0.5, quad * 0.25);
#endif
  return v;
}

// The pixel shader's use of the attributes: a negligible term it cannot drop.
float4 Extra(QuadVertex v) {
#ifdef ATTRIBUTES
  return (v.extra0 + v.extra1 + v.extra2) * 1e-12;
#else
  return 0;
#endif
}

QuadVertex VSTiles(uint id : SV_VertexID) {
  const float2 corners[6] = {float2(0, 0), float2(1, 0), float2(0, 1), float2(0, 1), float2(1, 0), float2(1, 1)};
  return MakeQuadVertex(id / 6, corners[id % 6]);
}

// --gs: the tiles travel as points and a geometry shader expands each into a
// quad, as document 000's billboard GS does with particles.
struct TilePoint {
  uint quad : QUAD;
};

TilePoint VSTilePoints(uint id : SV_VertexID) {
  TilePoint p;
  p.quad = id;
  return p;
}

[maxvertexcount(4)]
void GSTileQuad(point TilePoint input[1], inout TriangleStream<QuadVertex> stream) {
  const float2 corners[4] = {float2(0, 0), float2(1, 0), float2(0, 1), float2(1, 1)};
  for (uint i = 0; i < 4; ++i) {
    stream.Append(MakeQuadVertex(input[0].quad, corners[i]));
  }
}

// Small values (about 1/1000), so ONE/ONE blending into UNORM targets stays
// unsaturated for a while. SV_Target0 is scaled by Scale: with --large it gets
// about 1000, as Table 1's weighted accum colour does, while the other targets
// keep values in [0, 1], as revealage's alpha does.
float4 Value(float4 pos) { return (float4(1, 2, 3, 4) + Varying * frac(pos.xyxy * 0.37)) / 4096.0; }

// --opacity: alphas in [0.05, 0.8] that vary from pixel to pixel, as the
// smoke's do. Without it the outputs are ~1/4096, which UNORM8 targets round
// away: blending then leaves them at their clear values.
float4 AlphaLike(float4 pos) { return 0.05 + 0.75 * frac(pos.yxxy * float4(0.173, 0.311, 0.057, 0.29)); }

float4 First(QuadVertex v) {
  return (Opacity > 0 ? AlphaLike(v.position) / 1024.0 : Value(v.position)) * Scale + Extra(v);
}

float4 Other(float4 pos) { return Opacity > 0 ? AlphaLike(pos) : Value(pos.yxzw); }

float4 PSOneTarget(QuadVertex v) : SV_Target0 { return First(v); }

struct TwoTargets { float4 a : SV_Target0; float4 b : SV_Target1; };
TwoTargets PSTwoTargets(QuadVertex v) {
  TwoTargets o; o.a = First(v); o.b = Other(v.position); return o;
}

struct ThreeTargets { float4 a : SV_Target0; float4 b : SV_Target1; float4 c : SV_Target2; };
ThreeTargets PSThreeTargets(QuadVertex v) {
  ThreeTargets o;
  o.a = First(v); o.b = Other(v.position); o.c = Other(v.position.yxwz);
  return o;
}
)hlsl";

// One render target: its format and its blend (D3D11 factors; Src ONE, Dest
// ZERO with blending off).
struct Target {
  rhi::DXGI_FORMAT format;
  bool blend;
  rhi::BLEND src = rhi::BLEND_ONE;
  rhi::BLEND dest = rhi::BLEND_ONE;
};

struct TargetSet {
  const char* name;
  std::vector<Target> targets;
};

const std::vector<TargetSet>& TargetSets() {
  using enum rhi::DXGI_FORMAT;
  using enum rhi::BLEND;
  const Target rgba8{DXGI_FORMAT_R8G8B8A8_UNORM, true}, rgba16f{DXGI_FORMAT_R16G16B16A16_FLOAT, true},
      r8{DXGI_FORMAT_R8_UNORM, true}, revealage{DXGI_FORMAT_R8_UNORM, true, BLEND_ZERO, BLEND_INV_SRC_COLOR},
      frame{DXGI_FORMAT_R8G8B8A8_UNORM, true, BLEND_ZERO, BLEND_INV_SRC_COLOR};
  static const std::vector<TargetSet> sets = {
      {"RGBA8, blending off", {{DXGI_FORMAT_R8G8B8A8_UNORM, false}}},
      {"RGBA8 (alpha blending's one target)", {rgba8}},
      {"RGBA16F", {rgba16f}},
      {"R8", {r8}},
      {"R8 ZERO/INV_SRC_COLOR", {revealage}},
      {"RGBA8 + RGBA8", {rgba8, rgba8}},
      {"RGBA8 + R8", {rgba8, r8}},
      {"RGBA8 + R8 ZERO/INV_SRC_COLOR", {rgba8, revealage}},
      {"R8 + R8", {r8, r8}},
      {"RGBA16F + RGBA16F", {rgba16f, rgba16f}},
      {"RGBA16F + RGBA8", {rgba16f, rgba8}},
      {"RGBA16F + R16F", {rgba16f, {DXGI_FORMAT_R16_FLOAT, true}}},
      {"RGBA16F + RG16F", {rgba16f, {DXGI_FORMAT_R16G16_FLOAT, true}}},
      {"RGBA16F + R8", {rgba16f, r8}},
      {"Table 1: RGBA16F + R8 ZERO/INV_SRC_COLOR", {rgba16f, revealage}},
      {"Table 3: Table 1 + RGBA8 ZERO/INV_SRC_COLOR", {rgba16f, revealage, frame}},
  };
  return sets;
}

[[noreturn]] void Fail(const std::string& what) {
  std::fprintf(stderr, "blend_fill_bench: %s\n", what.c_str());
  std::exit(2);
}

void Check(rhi::HRESULT hr, const char* what) {
  if (hr != rhi::S_OK) Fail(std::string(what) + " failed");
}

std::vector<uint32_t> Compile(const char* entry, const char* profile, bool attributes) {
  hlsl::CompileRequest request;
  request.source = kHlsl;
  if (attributes) request.defines.push_back({"ATTRIBUTES", "1"});
  request.fileName = "blend_fill_bench.hlsl";
  request.entryPoint = entry;
  request.profile = profile;
  hlsl::CompileResult result = hlsl::CompileHlsl(request);
  if (!result.ok) Fail(std::string("compiling ") + entry + ":\n" + result.FormatErrors());
  return std::move(result.spirv);
}

struct Options {
  rhi::UINT width = 1280, height = 720;
  int draws = 32;
  int repeats = 7;
  bool varying = false;  // outputs differ from pixel to pixel
  bool depth = false;    // a D32 depth buffer, tested LESS against 1.0 and not written (the 3D pass's state)
  int overlap = 1;       // each tile drawn this many times in a row (divides draws)
  bool sampled = false;  // targets also BIND_SHADER_RESOURCE, as the OIT targets the compose pass reads
  bool geometryShader = false;  // tiles as points expanded by a GS
  bool jitter = false;          // quads offset at random by up to half a tile
  bool large = false;           // SV_Target0 gets ~1000 (WBOIT-like accum values)
  bool opacity = false;         // every target gets alpha-like values, as the smoke's are
  bool attributes = false;      // 12 more interpolated floats into the pixel shader
};

// The switches, each setting one Options flag.
constexpr std::pair<const char*, bool Options::*> kSwitches[] = {
    {"--varying", &Options::varying}, {"--depth", &Options::depth},   {"--sampled", &Options::sampled},
    {"--gs", &Options::geometryShader}, {"--jitter", &Options::jitter}, {"--large", &Options::large},
    {"--opacity", &Options::opacity}, {"--attributes", &Options::attributes},
};

bool ParseSwitch(const std::string& arg, Options* options) {
  for (const auto& [name, flag] : kSwitches)
    if (arg == name) return options->*flag = true;
  return false;
}

Options ParseOptions(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const char* value = i + 1 < argc ? argv[i + 1] : nullptr;
    if (arg == "--size" && value && std::sscanf(value, "%ux%u", &options.width, &options.height) == 2 &&
        options.width > 0 && options.height > 0) {
      ++i;
    } else if (arg == "--draws" && value && (options.draws = std::atoi(value)) > 0) {
      ++i;
    } else if (arg == "--repeats" && value && (options.repeats = std::atoi(value)) > 0) {
      ++i;
    } else if (arg == "--overlap" && value && (options.overlap = std::atoi(value)) > 0) {
      ++i;
    } else if (!ParseSwitch(arg, &options)) {
      Fail("usage: blend_fill_bench [--size WxH] [--draws N>0] [--repeats R>0] [--varying] [--depth] "
           "[--overlap L dividing N] [--sampled] [--gs] [--jitter] [--large] [--opacity] [--attributes] "
           "(bad argument '" +
           arg + "')");
    }
  }
  if (options.draws % options.overlap != 0) Fail("--overlap must divide --draws");
  return options;
}

class Probe {
 public:
  explicit Probe(const Options& options) : options_(options) {
    rhi::DEVICE_OPTIONS deviceOptions;
    deviceOptions.OnMessage = [](rhi::MESSAGE_CATEGORY, rhi::MESSAGE_SEVERITY severity, const char* text) {
      if (severity <= rhi::MESSAGE_SEVERITY_WARNING) Fail(text);
    };
    Check(rhi::CreateDevice(&deviceOptions, device_.GetAddressOf(), context_.GetAddressOf()), "CreateDevice");
    CreateShaders();
    CreateConstants();
    CreateStates();
    CreateQueries();
    if (options.depth) CreateDepthBuffer();
  }

  std::string AdapterName() { return device_->GetAdapterName(); }
  // Fragments that reached the targets in the latest measurement (an OCCLUSION query).
  double Fragments() const { return static_cast<double>(fragments_); }

  // The median GPU milliseconds of `repeats` measurements of `draws` screen-covering
  // layers into the set (one untimed measurement first builds the pipeline).
  double MedianMilliseconds(const TargetSet& set) {
    std::vector<ComPtr<rhi::Texture2D>> textures;
    std::vector<ComPtr<rhi::RenderTargetView>> views;
    std::vector<rhi::RenderTargetView*> bound;
    for (const Target& target : set.targets) {
      const rhi::UINT bind = rhi::BIND_RENDER_TARGET | (options_.sampled ? rhi::BIND_SHADER_RESOURCE : 0u);
      textures.push_back(CreateScreenTexture(target.format, bind));
      views.emplace_back();
      Check(device_->CreateRenderTargetView(textures.back().Get(), nullptr, views.back().GetAddressOf()),
            "CreateRenderTargetView");
      bound.push_back(views.back().Get());
    }
    ComPtr<rhi::BlendState> blend;
    const rhi::BLEND_DESC blendDesc = BlendDescOf(set);
    Check(device_->CreateBlendState(&blendDesc, blend.GetAddressOf()), "CreateBlendState");
    std::vector<double> milliseconds;
    for (int i = 0; i <= options_.repeats; ++i) {
      const double ms = MeasureOnce(bound, blend.Get());
      if (i > 0 && ms > 0) milliseconds.push_back(ms);
    }
    context_->ClearState();
    if (milliseconds.empty()) Fail(std::string("every measurement of ") + set.name + " was disjoint");
    if (fragments_ == 0) Fail(std::string("no fragment reached the targets of ") + set.name);
    std::sort(milliseconds.begin(), milliseconds.end());
    return milliseconds[milliseconds.size() / 2];
  }

 private:
  void CreateShaders() {
    const bool attributes = options_.attributes;
    const std::vector<uint32_t> vs =
        Compile(options_.geometryShader ? "VSTilePoints" : "VSTiles", "vs_5_0", attributes);
    Check(device_->CreateVertexShader(vs.data(), vs.size() * 4, nullptr, vs_.GetAddressOf()), "CreateVertexShader");
    if (options_.geometryShader) {
      const std::vector<uint32_t> gs = Compile("GSTileQuad", "gs_5_0", attributes);
      Check(device_->CreateGeometryShader(gs.data(), gs.size() * 4, nullptr, gs_.GetAddressOf()),
            "CreateGeometryShader");
    }
    const char* pixelShaders[3] = {"PSOneTarget", "PSTwoTargets", "PSThreeTargets"};
    for (int i = 0; i < 3; ++i) {
      const std::vector<uint32_t> ps = Compile(pixelShaders[i], "ps_5_0", attributes);
      Check(device_->CreatePixelShader(ps.data(), ps.size() * 4, nullptr, ps_[i].GetAddressOf()), "CreatePixelShader");
    }
  }

  // Probe.Scale: SV_Target0's ~1/4096 (or, with --opacity, alpha/1024) made ~1000
  // with --large, else ~1/4096 (or the alpha itself).
  float Scale() const {
    if (options_.opacity) return options_.large ? 1024.0f * 1000.0f : 1024.0f;
    return options_.large ? 4096.0f * 256.0f : 1.0f;
  }

  // cbuffer Probe of the HLSL above.
  void CreateConstants() {
    struct {
      float varying;
      uint32_t layers;
      float jitter;
      float scale;
      float opacity;
      float padding[3];  // a cbuffer's size is a multiple of 16 bytes
    } probeConstants{options_.varying ? 1.0f : 0.0f,           static_cast<uint32_t>(options_.overlap),
                     options_.jitter ? 1.0f : 0.0f,            Scale(),
                     options_.opacity ? 1.0f : 0.0f,           {}};
    rhi::BUFFER_DESC desc{sizeof probeConstants, rhi::USAGE_IMMUTABLE, rhi::BIND_CONSTANT_BUFFER, 0, 0, 0};
    rhi::SUBRESOURCE_DATA data{&probeConstants, 0, 0};
    Check(device_->CreateBuffer(&desc, &data, constants_.GetAddressOf()), "CreateBuffer");
  }

  void CreateStates() {
    rhi::RASTERIZER_DESC noCull{};
    noCull.CullMode = rhi::CULL_NONE;
    Check(device_->CreateRasterizerState(&noCull, rasterizer_.GetAddressOf()), "CreateRasterizerState");
    rhi::DEPTH_STENCIL_DESC depthState{};
    depthState.DepthEnable = options_.depth ? rhi::TRUE : rhi::FALSE;
    depthState.DepthWriteMask = rhi::DEPTH_WRITE_MASK_ZERO;
    depthState.DepthFunc = rhi::COMPARISON_LESS;
    Check(device_->CreateDepthStencilState(&depthState, depth_.GetAddressOf()), "CreateDepthStencilState");
  }

  void CreateQueries() {
    rhi::QUERY_DESC disjointDesc{rhi::QUERY_TIMESTAMP_DISJOINT, 0}, stampDesc{rhi::QUERY_TIMESTAMP, 0},
        occlusionDesc{rhi::QUERY_OCCLUSION, 0};
    Check(device_->CreateQuery(&disjointDesc, disjoint_.GetAddressOf()), "CreateQuery(TIMESTAMP_DISJOINT)");
    Check(device_->CreateQuery(&stampDesc, begin_.GetAddressOf()), "CreateQuery(TIMESTAMP)");
    Check(device_->CreateQuery(&stampDesc, end_.GetAddressOf()), "CreateQuery(TIMESTAMP)");
    Check(device_->CreateQuery(&occlusionDesc, samples_.GetAddressOf()), "CreateQuery(OCCLUSION)");
  }

  // D3D11 forbids colour factors for alpha: each colour factor's alpha twin.
  static rhi::BLEND AlphaFactor(rhi::BLEND colorFactor) {
    switch (colorFactor) {
      case rhi::BLEND_SRC_COLOR: return rhi::BLEND_SRC_ALPHA;
      case rhi::BLEND_INV_SRC_COLOR: return rhi::BLEND_INV_SRC_ALPHA;
      default: return colorFactor;
    }
  }

  static rhi::BLEND_DESC BlendDescOf(const TargetSet& set) {
    rhi::BLEND_DESC desc{};
    desc.IndependentBlendEnable = rhi::TRUE;
    for (size_t i = 0; i < set.targets.size(); ++i) {
      const Target& target = set.targets[i];
      rhi::RENDER_TARGET_BLEND_DESC& rt = desc.RenderTarget[i];
      rt.BlendEnable = target.blend ? rhi::TRUE : rhi::FALSE;
      if (!target.blend) continue;
      rt.SrcBlend = target.src;
      rt.DestBlend = target.dest;
      rt.SrcBlendAlpha = AlphaFactor(target.src);
      rt.DestBlendAlpha = AlphaFactor(target.dest);
    }
    return desc;
  }

  // A single-sample texture of the measured size.
  ComPtr<rhi::Texture2D> CreateScreenTexture(rhi::DXGI_FORMAT format, rhi::UINT bindFlags) {
    const rhi::TEXTURE2D_DESC desc{options_.width, options_.height, 1, 1, format, {1, 0}, rhi::USAGE_DEFAULT,
                                   bindFlags, 0, 0};
    ComPtr<rhi::Texture2D> texture;
    Check(device_->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()), "CreateTexture2D");
    return texture;
  }

  void CreateDepthBuffer() {
    depthTexture_ = CreateScreenTexture(rhi::DXGI_FORMAT_D32_FLOAT, rhi::BIND_DEPTH_STENCIL);
    Check(device_->CreateDepthStencilView(depthTexture_.Get(), nullptr, depthView_.GetAddressOf()),
          "CreateDepthStencilView");
  }

  // GPU milliseconds of one measurement, or 0 when the timestamps were disjoint.
  double MeasureOnce(const std::vector<rhi::RenderTargetView*>& targets, rhi::BlendState* blend) {
    rhi::DeviceContext* ctx = context_.Get();
    const float clear[4] = {0, 0, 0, 0};
    for (rhi::RenderTargetView* target : targets) ctx->ClearRenderTargetView(target, clear);
    if (depthView_) ctx->ClearDepthStencilView(depthView_.Get(), rhi::CLEAR_DEPTH, 1.0f, 0);
    ctx->OMSetRenderTargets(static_cast<rhi::UINT>(targets.size()), targets.data(), depthView_.Get());
    ctx->OMSetBlendState(blend, nullptr, rhi::DEFAULT_SAMPLE_MASK);
    ctx->OMSetDepthStencilState(depth_.Get(), 0);
    ctx->RSSetState(rasterizer_.Get());
    const rhi::VIEWPORT viewport{0, 0, static_cast<float>(options_.width), static_cast<float>(options_.height), 0, 1};
    ctx->RSSetViewports(1, &viewport);
    ctx->IASetInputLayout(nullptr);
    ctx->IASetPrimitiveTopology(gs_ ? rhi::PRIMITIVE_TOPOLOGY_POINTLIST : rhi::PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    ctx->VSSetShader(vs_.Get(), nullptr, 0);
    ctx->GSSetShader(gs_.Get(), nullptr, 0);
    ctx->PSSetShader(ps_[targets.size() - 1].Get(), nullptr, 0);
    rhi::Buffer* constants = constants_.Get();
    ctx->VSSetConstantBuffers(0, 1, &constants);
    ctx->GSSetConstantBuffers(0, 1, &constants);
    ctx->PSSetConstantBuffers(0, 1, &constants);
    ctx->Begin(disjoint_.Get());
    ctx->End(begin_.Get());
    ctx->Begin(samples_.Get());
    // Each draw covers the screen `overlap` times: 16x9 tiles of 6 vertices each (1 point with --gs).
    const rhi::UINT vertices = (gs_ ? 1 : 6) * 16 * 9 * static_cast<rhi::UINT>(options_.overlap);
    for (int i = 0; i < options_.draws / options_.overlap; ++i) ctx->Draw(vertices, 0);
    ctx->End(samples_.Get());
    ctx->End(end_.Get());
    ctx->End(disjoint_.Get());
    ctx->Flush();
    rhi::QUERY_DATA_TIMESTAMP_DISJOINT frequency{};
    rhi::UINT64 t0 = 0, t1 = 0;
    Check(rhi::WaitForData(ctx, disjoint_.Get(), &frequency), "GetData(TIMESTAMP_DISJOINT)");
    Check(rhi::WaitForData(ctx, begin_.Get(), &t0), "GetData(TIMESTAMP)");
    Check(rhi::WaitForData(ctx, end_.Get(), &t1), "GetData(TIMESTAMP)");
    Check(rhi::WaitForData(ctx, samples_.Get(), &fragments_), "GetData(OCCLUSION)");
    if (frequency.Disjoint || frequency.Frequency == 0) return 0;
    return 1000.0 * static_cast<double>(t1 - t0) / static_cast<double>(frequency.Frequency);
  }

  Options options_;
  ComPtr<rhi::Device> device_;
  ComPtr<rhi::DeviceContext> context_;
  ComPtr<rhi::VertexShader> vs_;
  ComPtr<rhi::GeometryShader> gs_;  // with --gs only
  ComPtr<rhi::PixelShader> ps_[3];
  ComPtr<rhi::Buffer> constants_;
  ComPtr<rhi::Texture2D> depthTexture_;
  ComPtr<rhi::DepthStencilView> depthView_;
  ComPtr<rhi::RasterizerState> rasterizer_;
  ComPtr<rhi::DepthStencilState> depth_;
  ComPtr<rhi::Query> disjoint_, begin_, end_;
  ComPtr<rhi::Query> samples_;  // OCCLUSION: the fragments that reached the targets
  rhi::UINT64 fragments_ = 0;   // of the latest measurement
};

}  // namespace

const char* ValuesDescription(const Options& options) {
  if (options.opacity) return options.large ? "alphas 0.05-0.8, SV_Target0's times 1000" : "alphas 0.05-0.8";
  return options.large ? "SV_Target0 ~1000, the others ~1/1000" : "~1/1000";
}

int main(int argc, char** argv) {
  const Options options = ParseOptions(argc, argv);
  Probe probe(options);
  std::printf("device: %s; %d layers of 16x9 tiles covering %ux%u, median of %d; ", probe.AdapterName().c_str(),
              options.draws, options.width, options.height, options.repeats);
  std::printf("outputs %s (%s), depth test %s, each tile drawn %d time(s) in a row%s, targets %s, tiles %s, %s\n\n",
              options.varying || options.opacity ? "varying per pixel" : "uniform",
              ValuesDescription(options),
              options.depth ? "LESS against 1.0, no write" : "off", options.overlap,
              options.jitter ? " at random offsets" : "",
              options.sampled ? "also shader resources" : "render targets only",
              options.geometryShader ? "points expanded by a GS" : "triangles",
              options.attributes ? "12 interpolated floats besides the position" : "the position alone interpolated");
  std::printf("| render targets (ONE/ONE unless named) | GPU ms | M fragments | G fragments/s | time / one RGBA8 |\n");
  std::printf("|---|---:|---:|---:|---:|\n");
  double reference = 0;
  for (const TargetSet& set : TargetSets()) {
    const double ms = probe.MedianMilliseconds(set);
    if (reference == 0 && set.targets.size() == 1 && set.targets[0].blend) reference = ms;
    char relative[32] = "-";
    if (reference > 0) std::snprintf(relative, sizeof relative, "%.2f", ms / reference);
    std::printf("| %s | %.3f | %.1f | %.2f | %s |\n", set.name, ms, probe.Fragments() * 1e-6,
                probe.Fragments() / (ms * 1e-3) * 1e-9, relative);
  }
  return 0;
}
