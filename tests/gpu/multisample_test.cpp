// Multisampling for order-independent transparency: multisampled targets of
// every format the OIT methods use, with 2, 4 and 8 samples where the device
// has them (the others refused with the reason); per-sample shading
// (SV_SampleIndex) read back sample by sample through Texture2DMS.Load;
// SV_Coverage in and out; GetSamplePosition; resolves (the average of the
// samples) through ResolveSubresource and CaptureTexture2D. Every expected
// value comes from D3D11's standard sample pattern, written out below.
#include <bit>
#include <cmath>
#include <cstring>
#include <string>
#include <tuple>

#include "gpu_helpers.h"
#include "rhi/capture.h"

namespace rhi_test {
namespace {

using namespace rhi;

// D3D11_STANDARD_MULTISAMPLE_PATTERN, in 1/16 pixel from the pixel centre
// (D3D11_STANDARD_MULTISAMPLE_QUALITY_LEVELS documentation).
struct SampleOffset {
  int x, y;
};
std::vector<SampleOffset> StandardPattern(UINT samples) {
  switch (samples) {
    case 2: return {{4, 4}, {-4, -4}};
    case 4: return {{-2, -6}, {6, -2}, {-6, 2}, {2, 6}};
    case 8: return {{1, -3}, {-1, 3}, {5, 1}, {-3, -5}, {-5, 5}, {-7, -1}, {3, 7}, {7, -7}};
    default: return {{0, 0}};
  }
}

// The scene of the coverage tests: one triangle whose right edge is the
// vertical x = 4.5 across an 8x2 target and whose other edges lie outside it
// (a quad's diagonal would split pixels between two primitives, and so would
// clipping: the viewport is larger than the target instead). Pixels 0-3
// are covered, 5-7 not; pixel 4's edge runs through its centre, so exactly its
// samples left of the centre (x offset < 0) are covered.
constexpr UINT kW = 8, kH = 2;
constexpr float kEdge = 4.5f;
bool Covered(UINT x, UINT sample, UINT samples) {
  return float(x) + 0.5f + float(StandardPattern(samples)[sample].x) / 16.0f < kEdge;
}
UINT CoverageMaskOfPixel4(UINT samples) {
  UINT mask = 0;
  for (UINT s = 0; s < samples; ++s) mask |= Covered(4, s, samples) ? 1u << s : 0u;
  return mask;
}

struct FormatCase {
  DXGI_FORMAT format;
  const char* name;
  UINT channels;
};
const FormatCase kOitFormats[] = {
    {DXGI_FORMAT_R8G8B8A8_UNORM, "R8G8B8A8_UNORM", 4},   {DXGI_FORMAT_R8G8B8A8_UNORM_SRGB, "R8G8B8A8_UNORM_SRGB", 4},
    {DXGI_FORMAT_R16G16B16A16_FLOAT, "R16G16B16A16_FLOAT", 4}, {DXGI_FORMAT_R16_FLOAT, "R16_FLOAT", 1},
    {DXGI_FORMAT_R8_UNORM, "R8_UNORM", 1},               {DXGI_FORMAT_R32_FLOAT, "R32_FLOAT", 1},
    {DXGI_FORMAT_R32G32_FLOAT, "R32G32_FLOAT", 2},       {DXGI_FORMAT_R32G32B32A32_FLOAT, "R32G32B32A32_FLOAT", 4},
};
constexpr UINT kCounts[] = {2, 4, 8};

using MsaaParam = std::tuple<FormatCase, UINT>;

std::string ParamName(const ::testing::TestParamInfo<MsaaParam>& info) {
  return std::string(std::get<0>(info.param).name) + "_x" + std::to_string(std::get<1>(info.param));
}

class MultisampleTest : public RhiGpuTest, public ::testing::WithParamInterface<MsaaParam> {
 protected:
  DXGI_FORMAT format() const { return std::get<0>(GetParam()).format; }
  UINT channels() const { return std::get<0>(GetParam()).channels; }
  UINT samples() const { return std::get<1>(GetParam()); }
  // Skips the test where the device has no such target (MultisampleCreationTest covers the refusal).
  bool Supported() {
    UINT levels = 0;
    EXPECT_EQ(device->CheckMultisampleQualityLevels(format(), samples(), &levels), S_OK);
    return levels > 0;
  }
  struct MsTarget {
    ComPtr<Texture2D> texture;
    ComPtr<RenderTargetView> rtv;
    ComPtr<ShaderResourceView> srv;
  };
  MsTarget MakeMsTarget() {
    MsTarget t;
    t.texture = MakeTexture(kW, kH, format(), BIND_RENDER_TARGET | BIND_SHADER_RESOURCE, samples());
    EXPECT_EQ(device->CreateRenderTargetView(t.texture.Get(), nullptr, t.rtv.GetAddressOf()), S_OK);
    EXPECT_EQ(device->CreateShaderResourceView(t.texture.Get(), nullptr, t.srv.GetAddressOf()), S_OK);
    return t;
  }
  // Draws the coverage scene's triangle, white, into `rtv` with `ps` (the colour pipeline's VS and layout).
  void DrawEdgeTriangle(RenderTargetView* rtv, PixelShader* ps) {
    UseColorPipeline();
    context->PSSetShader(ps, nullptr, 0);
    context->OMSetRenderTargets(1, &rtv, nullptr);
    // A 128x128 viewport from (-60, -60): the triangle lies inside the clip volume.
    constexpr float kLeft = -60, kTop = -60, kSize = 128;
    const VIEWPORT viewport{kLeft, kTop, kSize, kSize, 0, 1};
    context->RSSetViewports(1, &viewport);
    auto vertex = [&](float px, float py) {
      return Vertex{(px - kLeft) / kSize * 2 - 1, 1 - (py - kTop) / kSize * 2, 0.5f, kWhite};
    };
    // Clockwise on screen: down the edge, then out to the far left.
    DrawVertices({vertex(kEdge, -20), vertex(kEdge, 20), vertex(-40, 0)});
  }
};

// CheckMultisampleQualityLevels and CreateTexture2D agree: a count with one
// quality level is created, a count with none is refused naming it. Vulkan
// requires 4 samples for every colour attachment format, so 4 always exists.
class MultisampleCreationTest : public MultisampleTest {};

TEST_P(MultisampleCreationTest, CreationFollowsCheckMultisampleQualityLevels) {
  UINT levels = 99;
  ASSERT_EQ(device->CheckMultisampleQualityLevels(format(), samples(), &levels), S_OK);
  ASSERT_LE(levels, 1u);
  if (samples() == 4) EXPECT_EQ(levels, 1u) << "Vulkan guarantees 4 samples for colour attachments";
  TEXTURE2D_DESC desc{kW, kH, 1, 1, format(), {samples(), 0}, USAGE_DEFAULT,
                      BIND_RENDER_TARGET | BIND_SHADER_RESOURCE, 0, 0};
  ComPtr<Texture2D> texture;
  const HRESULT hr = device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf());
  if (levels == 1) {
    EXPECT_EQ(hr, S_OK);
    EXPECT_TRUE(Refusals().empty()) << Refusals().front();
    desc.SampleDesc.Quality = STANDARD_MULTISAMPLE_PATTERN;
    EXPECT_EQ(device->CreateTexture2D(&desc, nullptr, texture.ReleaseAndGetAddressOf()), S_OK);
  } else {
    EXPECT_EQ(hr, E_INVALIDARG);
    EXPECT_FALSE(texture);
    EXPECT_TRUE(RefusedWith("SampleDesc.Count " + std::to_string(samples()) + " is not supported for DXGI_FORMAT_" +
                            std::get<0>(GetParam()).name));
  }
}

INSTANTIATE_TEST_SUITE_P(OitFormats, MultisampleCreationTest,
                         ::testing::Combine(::testing::ValuesIn(kOitFormats), ::testing::ValuesIn(kCounts)),
                         ParamName);

TEST_F(RhiGpuTest, MultisampleDescriptionsAndViewsAreRefusedWithReason) {
  const UINT bind = BIND_RENDER_TARGET | BIND_SHADER_RESOURCE;
  TEXTURE2D_DESC desc{4, 4, 1, 1, DXGI_FORMAT_R8G8B8A8_UNORM, {4, 1}, USAGE_DEFAULT, bind, 0, 0};
  ComPtr<Texture2D> texture;
  EXPECT_EQ(device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("SampleDesc.Quality 0x1 is not available for SampleDesc.Count 4"));
  desc.SampleDesc.Quality = CENTER_MULTISAMPLE_PATTERN;
  EXPECT_EQ(device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()), E_INVALIDARG);
  desc.SampleDesc = {1, STANDARD_MULTISAMPLE_PATTERN};
  EXPECT_EQ(device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("SampleDesc.Quality 0xFFFFFFFF is not available for SampleDesc.Count 1"));
  desc.SampleDesc = {4, 0};
  desc.BindFlags = bind | BIND_UNORDERED_ACCESS;
  EXPECT_EQ(device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("multisampled textures cannot have BIND_UNORDERED_ACCESS"));
  desc.BindFlags = bind;
  const uint32_t texels[16] = {};
  const SUBRESOURCE_DATA init{texels, 16, 64};
  EXPECT_EQ(device->CreateTexture2D(&desc, &init, texture.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("multisampled textures cannot be initialized with data"));

  ASSERT_EQ(device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()), S_OK);
  SHADER_RESOURCE_VIEW_DESC srv{};
  srv.Format = DXGI_FORMAT_R8G8B8A8_UNORM;
  srv.ViewDimension = SRV_DIMENSION_TEXTURE2D;
  srv.Texture2D = {0, 1};
  ComPtr<ShaderResourceView> view;
  EXPECT_EQ(device->CreateShaderResourceView(texture.Get(), &srv, view.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("needs a *_TEXTURE2DMS or *_TEXTURE2DMSARRAY ViewDimension"));
  ComPtr<Texture2D> single = MakeTexture(4, 4, DXGI_FORMAT_R8G8B8A8_UNORM, bind);
  srv.ViewDimension = SRV_DIMENSION_TEXTURE2DMS;
  EXPECT_EQ(device->CreateShaderResourceView(single.Get(), &srv, view.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("needs a multisampled texture"));
  RENDER_TARGET_VIEW_DESC rtv{DXGI_FORMAT_R8G8B8A8_UNORM, RTV_DIMENSION_TEXTURE2D, {}};
  ComPtr<RenderTargetView> target;
  EXPECT_EQ(device->CreateRenderTargetView(texture.Get(), &rtv, target.GetAddressOf()), E_INVALIDARG);

  UINT levels = 7;
  EXPECT_EQ(device->CheckMultisampleQualityLevels(DXGI_FORMAT_R8G8B8A8_UNORM, 3, &levels), S_OK);
  EXPECT_EQ(levels, 0u) << "3 is not a sample count";
  EXPECT_EQ(device->CheckMultisampleQualityLevels(DXGI_FORMAT_R8G8B8A8_TYPELESS, 4, &levels), E_INVALIDARG);
}

// ---------------------------------------------------------------------------
// Per-sample shading and coverage

// A pixel shader reading SV_SampleIndex runs once per sample: each sample
// receives its own index. Written as index / 8 and read back as round(v * 8),
// which every format of the list holds exactly enough; uncovered samples keep
// the clear value 1 (read back as 8).
class PerSampleShadingTest : public MultisampleTest {};

TEST_P(PerSampleShadingTest, EachSampleReceivesItsOwnSampleIndex) {
  if (!Supported()) GTEST_SKIP() << "no " << samples() << "x target of this format on " << device->GetAdapterName();
  MsTarget target = MakeMsTarget();
  Clear(target.rtv.Get(), {1, 1, 1, 1});
  ComPtr<PixelShader> ps = PS(R"(
    float4 main(float4 pos : SV_Position, uint s : SV_SampleIndex) : SV_Target { return (s / 8.0).xxxx; })");
  DrawEdgeTriangle(target.rtv.Get(), ps.Get());
  const std::vector<float> values = ReadSamples(target.srv.Get(), kW, kH, samples());
  for (UINT y = 0; y < kH; ++y)
    for (UINT x = 0; x < kW; ++x)
      for (UINT s = 0; s < samples(); ++s)
        for (UINT c = 0; c < channels(); ++c) {
          const float v = values[((y * kW + x) * samples() + s) * 4 + c];
          const float expected = Covered(x, s, samples()) ? float(s) : 8.0f;
          EXPECT_EQ(std::round(v * 8), expected) << "pixel (" << x << "," << y << ") sample " << s << " channel " << c;
        }
}

INSTANTIATE_TEST_SUITE_P(OitFormats, PerSampleShadingTest,
                         ::testing::Combine(::testing::ValuesIn(kOitFormats), ::testing::ValuesIn(kCounts)),
                         ParamName);

class CoverageTest : public MultisampleTest {};

// SV_Coverage as a pixel-shader input: the pixel's covered samples, as the
// standard pattern places them. Every covered sample stores the mask.
TEST_P(CoverageTest, InputCoverageIsTheMaskOfCoveredSamples) {
  if (!Supported()) GTEST_SKIP() << "no " << samples() << "x R32_FLOAT target on " << device->GetAdapterName();
  MsTarget target = MakeMsTarget();
  Clear(target.rtv.Get(), {-1, -1, -1, -1});
  // A member of the input struct: glslang's HLSL front end drops an SV_Coverage
  // input declared as a plain parameter, which the compiler therefore refuses.
  ComPtr<PixelShader> ps = PS(R"(
    struct PSIn { float4 pos : SV_Position; uint coverage : SV_Coverage; };
    float4 main(PSIn i) : SV_Target { return float(i.coverage).xxxx; })");
  DrawEdgeTriangle(target.rtv.Get(), ps.Get());
  const std::vector<float> values = ReadSamples(target.srv.Get(), kW, kH, samples());
  const UINT full = (1u << samples()) - 1;
  for (UINT x = 0; x < kW; ++x)
    for (UINT s = 0; s < samples(); ++s) {
      const float expected = !Covered(x, s, samples()) ? -1.0f : x == 4 ? float(CoverageMaskOfPixel4(samples()))
                                                                         : float(full);
      EXPECT_EQ(values[(x * samples() + s) * 4], expected) << "pixel " << x << " sample " << s;
    }
}

// SV_Coverage as an output: samples outside the written mask keep their value.
TEST_P(CoverageTest, OutputCoverageSelectsTheWrittenSamples) {
  if (!Supported()) GTEST_SKIP() << "no " << samples() << "x R32_FLOAT target on " << device->GetAdapterName();
  MsTarget target = MakeMsTarget();
  Clear(target.rtv.Get(), {-1, -1, -1, -1});
  // Odd-numbered samples only.
  ComPtr<PixelShader> ps = PS(R"(
    struct PSOut { float4 color : SV_Target; uint coverage : SV_Coverage; };
    PSOut main(float4 pos : SV_Position) { PSOut o; o.color = 1; o.coverage = 0xAAAAAAAA; return o; })");
  DrawEdgeTriangle(target.rtv.Get(), ps.Get());
  const std::vector<float> values = ReadSamples(target.srv.Get(), kW, kH, samples());
  for (UINT x = 0; x < kW; ++x)
    for (UINT s = 0; s < samples(); ++s) {
      const float expected = Covered(x, s, samples()) && s % 2 == 1 ? 1.0f : -1.0f;
      EXPECT_EQ(values[(x * samples() + s) * 4], expected) << "pixel " << x << " sample " << s;
    }
}

INSTANTIATE_TEST_SUITE_P(R32Float, CoverageTest,
                         ::testing::Combine(::testing::Values(FormatCase{DXGI_FORMAT_R32_FLOAT, "R32_FLOAT", 1}),
                                            ::testing::ValuesIn(kCounts)),
                         ParamName);

// Texture2DMS.GetSamplePosition: glslang's HLSL front end lowers it to a table
// of D3D11's standard positions chosen by the texture's sample count (there is
// no Vulkan query); they must be D3D11's, in pixels from the centre.
class SamplePositionTest : public MultisampleTest {};

TEST_P(SamplePositionTest, GetSamplePositionIsTheStandardPattern) {
  if (!Supported()) GTEST_SKIP() << "no " << samples() << "x R32_FLOAT target on " << device->GetAdapterName();
  MsTarget source = MakeMsTarget();
  ComPtr<Texture2D> out = MakeTexture(samples(), 1, DXGI_FORMAT_R32G32B32A32_FLOAT, BIND_RENDER_TARGET);
  ComPtr<RenderTargetView> rtv;
  ASSERT_EQ(device->CreateRenderTargetView(out.Get(), nullptr, rtv.GetAddressOf()), S_OK);
  ComPtr<PixelShader> ps = PS(R"(
    Texture2DMS<float> T : register(t0);
    float4 main(float4 pos : SV_Position) : SV_Target { return float4(T.GetSamplePosition(uint(pos.x)), 0, 1); })");
  BindTarget(rtv.Get(), samples(), 1);
  ShaderResourceView* srvs[] = {source.srv.Get()};
  context->PSSetShaderResources(0, 1, srvs);
  DrawFullScreen(ps.Get());
  const std::vector<float> positions = ReadFloats(out.Get());
  const std::vector<SampleOffset> pattern = StandardPattern(samples());
  for (UINT s = 0; s < samples(); ++s) {
    EXPECT_EQ(positions[s * 4 + 0], pattern[s].x / 16.0f) << "sample " << s << " x";
    EXPECT_EQ(positions[s * 4 + 1], pattern[s].y / 16.0f) << "sample " << s << " y";
  }
}

// GetRenderTargetSamplePosition (which the HLSL compiler supplies; glslang
// lacks it) gives the bound render targets' standard positions. Every sample
// of pixel x holds position x, so the resolve keeps it.
TEST_P(SamplePositionTest, GetRenderTargetSamplePositionIsTheStandardPatternOfTheTargets) {
  if (!Supported()) GTEST_SKIP() << "no " << samples() << "x target on " << device->GetAdapterName();
  ComPtr<Texture2D> out = MakeTexture(samples() + 1, 1, DXGI_FORMAT_R32G32B32A32_FLOAT, BIND_RENDER_TARGET, samples());
  ComPtr<RenderTargetView> rtv;
  ASSERT_EQ(device->CreateRenderTargetView(out.Get(), nullptr, rtv.GetAddressOf()), S_OK);
  ComPtr<PixelShader> ps = PS(R"(float4 main(float4 pos : SV_Position) : SV_Target {
      return float4(GetRenderTargetSamplePosition(int(pos.x)), 0, 1); })");
  BindTarget(rtv.Get(), samples() + 1, 1);
  DrawFullScreen(ps.Get());
  const std::vector<float> positions = ReadFloats(out.Get());
  const std::vector<SampleOffset> pattern = StandardPattern(samples());
  for (UINT s = 0; s < samples(); ++s) {
    EXPECT_EQ(positions[s * 4 + 0], pattern[s].x / 16.0f) << "sample " << s << " x";
    EXPECT_EQ(positions[s * 4 + 1], pattern[s].y / 16.0f) << "sample " << s << " y";
  }
  EXPECT_EQ(positions[samples() * 4 + 0], 0.0f) << "an index past the count gives (0, 0)";
  EXPECT_EQ(positions[samples() * 4 + 1], 0.0f) << "an index past the count gives (0, 0)";
}

INSTANTIATE_TEST_SUITE_P(R32Float, SamplePositionTest,
                         ::testing::Combine(::testing::Values(FormatCase{DXGI_FORMAT_R32_FLOAT, "R32_FLOAT", 1}),
                                            ::testing::ValuesIn(kCounts)),
                         ParamName);

// ---------------------------------------------------------------------------
// Resolves

float HalfToFloat(uint16_t h) {
  const int exponent = (h >> 10) & 0x1F, mantissa = h & 0x3FF;
  const float magnitude = exponent == 0 ? std::ldexp(float(mantissa), -24)
                                        : std::ldexp(float(mantissa | 0x400), exponent - 25);
  return (h & 0x8000) ? -magnitude : magnitude;
}

float SrgbEncode(float linear) {
  return linear <= 0.0031308f ? linear * 12.92f : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

// Channel c of pixel x of a resolved row, as a float in the format's own
// encoding (UNORM: the stored integer).
float StoredChannel(const std::vector<uint8_t>& row, DXGI_FORMAT format, UINT channels, UINT x, UINT c) {
  switch (format) {
    case DXGI_FORMAT_R8G8B8A8_UNORM:
    case DXGI_FORMAT_R8G8B8A8_UNORM_SRGB:
    case DXGI_FORMAT_R8_UNORM: return row[x * channels + c];
    case DXGI_FORMAT_R16G16B16A16_FLOAT:
    case DXGI_FORMAT_R16_FLOAT: {
      uint16_t h;
      std::memcpy(&h, row.data() + (x * channels + c) * 2, 2);
      return HalfToFloat(h);
    }
    default: {
      float f;
      std::memcpy(&f, row.data() + (x * channels + c) * 4, 4);
      return f;
    }
  }
}

// What D3D11 stores for the average `linear` of the samples: UNORM rounds
// (within one unit, D3D11's resolve tolerance), sRGB averages in linear space
// and encodes, floats hold k/n exactly.
void ExpectResolved(float got, DXGI_FORMAT format, UINT channel, float linear, const std::string& where) {
  switch (format) {
    case DXGI_FORMAT_R8G8B8A8_UNORM:
    case DXGI_FORMAT_R8_UNORM: EXPECT_NEAR(got, linear * 255, 1.0f) << where; break;
    case DXGI_FORMAT_R8G8B8A8_UNORM_SRGB:
      EXPECT_NEAR(got, (channel == 3 ? linear : SrgbEncode(linear)) * 255, 1.0f) << where;
      break;
    default: EXPECT_EQ(got, linear) << where;
  }
}

class ResolveTest : public MultisampleTest {};

// White over black: pixels 0-3 resolve to 1, 5-7 to 0, pixel 4 to the share of
// its samples the quad covers. ResolveSubresource and CaptureTexture2D (which
// resolves a multisampled texture itself) give the same bytes.
TEST_P(ResolveTest, ResolveIsTheAverageOfTheSamples) {
  if (!Supported()) GTEST_SKIP() << "no " << samples() << "x target of this format on " << device->GetAdapterName();
  MsTarget target = MakeMsTarget();
  Clear(target.rtv.Get(), {0, 0, 0, 0});
  UseColorPipeline();
  DrawEdgeTriangle(target.rtv.Get(), colorPS_.Get());
  ComPtr<Texture2D> resolved = MakeTexture(kW, kH, format(), BIND_SHADER_RESOURCE);
  context->ResolveSubresource(resolved.Get(), 0, target.texture.Get(), 0, format());
  const std::vector<uint8_t> viaResolve = ReadTexture(resolved.Get());
  std::vector<uint8_t> viaCapture;
  ASSERT_EQ(CaptureTexture2D(device.Get(), context.Get(), target.texture.Get(), 0, &viaCapture), S_OK);
  EXPECT_EQ(viaCapture, viaResolve);
  const UINT covered4 = std::popcount(CoverageMaskOfPixel4(samples()));
  for (UINT x = 0; x < kW; ++x) {
    const float share = x < 4 ? 1.0f : x == 4 ? float(covered4) / float(samples()) : 0.0f;
    for (UINT c = 0; c < channels(); ++c)
      ExpectResolved(StoredChannel(viaResolve, format(), channels(), x, c), format(), c, share,
                     "pixel " + std::to_string(x) + " channel " + std::to_string(c));
  }
  EXPECT_TRUE(Refusals().empty()) << Refusals().front();
}

INSTANTIATE_TEST_SUITE_P(OitFormats, ResolveTest,
                         ::testing::Combine(::testing::ValuesIn(kOitFormats), ::testing::ValuesIn(kCounts)),
                         ParamName);

// Multisampled arrays: an RTV of one slice (RTV_DIMENSION_TEXTURE2DMSARRAY), a
// Texture2DMSArray SRV reading every slice and sample, and CaptureTexture2D of
// one slice (its subresource is the slice).
TEST_F(RhiGpuTest, MultisampledArraySlicesAreWrittenReadAndResolvedSeparately) {
  TEXTURE2D_DESC desc{4, 4, 1, 3, DXGI_FORMAT_R32_FLOAT, {4, 0}, USAGE_DEFAULT,
                      BIND_RENDER_TARGET | BIND_SHADER_RESOURCE, 0, 0};
  ComPtr<Texture2D> array;
  ASSERT_EQ(device->CreateTexture2D(&desc, nullptr, array.GetAddressOf()), S_OK);
  for (UINT slice = 0; slice < 3; ++slice) {
    RENDER_TARGET_VIEW_DESC rtvDesc{DXGI_FORMAT_R32_FLOAT, RTV_DIMENSION_TEXTURE2DMSARRAY, {}};
    rtvDesc.Texture2DMSArray = {slice, 1};
    ComPtr<RenderTargetView> rtv;
    ASSERT_EQ(device->CreateRenderTargetView(array.Get(), &rtvDesc, rtv.GetAddressOf()), S_OK);
    const float value = 10.0f * float(slice + 1);
    Clear(rtv.Get(), {value, value, value, value});
  }
  SHADER_RESOURCE_VIEW_DESC srvDesc{};
  srvDesc.Format = DXGI_FORMAT_R32_FLOAT;
  srvDesc.ViewDimension = SRV_DIMENSION_TEXTURE2DMSARRAY;
  srvDesc.Texture2DMSArray = {1, 2};  // slices 1 and 2
  ComPtr<ShaderResourceView> srv;
  ASSERT_EQ(device->CreateShaderResourceView(array.Get(), &srvDesc, srv.GetAddressOf()), S_OK);
  // Texel (x, y) of the 8x4 output: slice x / 4 of the view, sample x % 4, of pixel (0, y).
  Target out = MakeRenderTarget(8, 4, DXGI_FORMAT_R32_FLOAT);
  BindTarget(out.rtv.Get(), 8, 4);
  ShaderResourceView* srvs[] = {srv.Get()};
  context->PSSetShaderResources(0, 1, srvs);
  ComPtr<PixelShader> ps = PS(R"(Texture2DMSArray<float> T : register(t0);
      float4 main(float4 pos : SV_Position) : SV_Target {
        uint x = uint(pos.x);
        return T.Load(int3(0, pos.y, x / 4), x % 4).xxxx; })");
  DrawFullScreen(ps.Get());
  const std::vector<float> texels = ReadFloats(out.texture.Get());
  for (UINT y = 0; y < 4; ++y)
    for (UINT x = 0; x < 8; ++x) EXPECT_EQ(texels[y * 8 + x], x < 4 ? 20.0f : 30.0f) << "texel " << x << "," << y;
  std::vector<uint8_t> slice2;
  ASSERT_EQ(CaptureTexture2D(device.Get(), context.Get(), array.Get(), 2, &slice2), S_OK);
  float first;
  std::memcpy(&first, slice2.data(), 4);
  EXPECT_EQ(slice2.size(), 4u * 4 * 4);
  EXPECT_EQ(first, 30.0f);
}

// A typeless texture resolves as the Format ResolveSubresource names: two of
// four samples white (SampleMask 0x3) average to 0.5, stored as 127 or 128 in
// UNORM and, averaged in linear space, as 188 (sRGB of 0.5) in UNORM_SRGB.
TEST_F(RhiGpuTest, TypelessTexturesResolveAsTheFormatGiven) {
  const UINT bind = BIND_RENDER_TARGET | BIND_SHADER_RESOURCE;
  ComPtr<Texture2D> ms = MakeTexture(4, 4, DXGI_FORMAT_R8G8B8A8_TYPELESS, bind, 4);
  RENDER_TARGET_VIEW_DESC rtvDesc{DXGI_FORMAT_R8G8B8A8_UNORM, RTV_DIMENSION_TEXTURE2DMS, {}};
  ComPtr<RenderTargetView> rtv;
  ASSERT_EQ(device->CreateRenderTargetView(ms.Get(), &rtvDesc, rtv.GetAddressOf()), S_OK);
  Clear(rtv.Get(), {0, 0, 0, 0});
  UseColorPipeline();
  BindTarget(rtv.Get(), 4, 4);
  context->OMSetBlendState(nullptr, nullptr, 0x3);
  DrawVertices(Quad(0, 0, 4, 4, kWhite, 4, 4));
  context->OMSetBlendState(nullptr, nullptr, DEFAULT_SAMPLE_MASK);
  context->OMSetRenderTargets(0, nullptr, nullptr);

  ComPtr<Texture2D> unorm = MakeTexture(4, 4, DXGI_FORMAT_R8G8B8A8_TYPELESS, bind);
  context->ResolveSubresource(unorm.Get(), 0, ms.Get(), 0, DXGI_FORMAT_R8G8B8A8_UNORM);
  ComPtr<Texture2D> srgb = MakeTexture(4, 4, DXGI_FORMAT_R8G8B8A8_TYPELESS, bind);
  context->ResolveSubresource(srgb.Get(), 0, ms.Get(), 0, DXGI_FORMAT_R8G8B8A8_UNORM_SRGB);
  ASSERT_TRUE(Refusals().empty()) << Refusals().front();
  const std::vector<uint8_t> unormTexels = ReadTexture(unorm.Get()), srgbTexels = ReadTexture(srgb.Get());
  ASSERT_EQ(unormTexels.size(), 64u);
  for (UINT i = 0; i < 64; ++i) {
    EXPECT_NEAR(unormTexels[i], 127.5, 0.5) << "UNORM byte " << i;
    EXPECT_NEAR(srgbTexels[i], i % 4 == 3 ? 127.5 : 188.0, i % 4 == 3 ? 0.5 : 1.0) << "UNORM_SRGB byte " << i;
  }

  ComPtr<Texture2D> notTarget = MakeTexture(4, 4, DXGI_FORMAT_R8G8B8A8_TYPELESS, BIND_SHADER_RESOURCE);
  context->ResolveSubresource(notTarget.Get(), 0, ms.Get(), 0, DXGI_FORMAT_R8G8B8A8_UNORM);
  EXPECT_TRUE(RefusedWith("resolving a typeless resource as DXGI_FORMAT_R8G8B8A8_UNORM needs BIND_RENDER_TARGET"));
}

// What has no average is refused with the reason: integer and depth formats,
// in ResolveSubresource and in CaptureTexture2D.
TEST_F(RhiGpuTest, IntegerAndDepthMultisampledTexturesHaveNoResolve) {
  ComPtr<Texture2D> integer = MakeTexture(4, 4, DXGI_FORMAT_R32_UINT, BIND_RENDER_TARGET, 4);
  ComPtr<Texture2D> single = MakeTexture(4, 4, DXGI_FORMAT_R32_UINT, BIND_RENDER_TARGET);
  context->ResolveSubresource(single.Get(), 0, integer.Get(), 0, DXGI_FORMAT_R32_UINT);
  EXPECT_TRUE(RefusedWith("ResolveSubresource: DXGI_FORMAT_R32_UINT cannot be resolved"));
  std::vector<uint8_t> texels;
  EXPECT_EQ(CaptureTexture2D(device.Get(), context.Get(), integer.Get(), 0, &texels), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("DXGI_FORMAT_R32_UINT is an integer format, which has no resolve"));
  ComPtr<Texture2D> depth = MakeTexture(4, 4, DXGI_FORMAT_D32_FLOAT, BIND_DEPTH_STENCIL, 4);
  EXPECT_EQ(CaptureTexture2D(device.Get(), context.Get(), depth.Get(), 0, &texels), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("DXGI_FORMAT_D32_FLOAT is a depth format, which has no resolve"));
  ComPtr<Texture2D> color = MakeTexture(4, 4, DXGI_FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET, 4);
  ComPtr<Texture2D> wrongSize = MakeTexture(2, 2, DXGI_FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET);
  context->ResolveSubresource(wrongSize.Get(), 0, color.Get(), 0, DXGI_FORMAT_R8G8B8A8_UNORM);
  EXPECT_TRUE(RefusedWith("ResolveSubresource: source and destination sizes differ"));
}

}  // namespace
}  // namespace rhi_test
