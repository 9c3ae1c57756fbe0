// Document 001's WBOIT with MSAA (renderer/src/oit/wboit_msaa.cpp) against CPU
// models computed here from the method's own multisampled targets, read back
// sample by sample (Texture2DMS.Load): the per-sample composite and its resolve,
// the per-pixel resolve it is compared with, and the discussion's variants. The
// formulas are written out below from document 001 (SPEC.md "001"), not taken
// from the shader; only the exposure constant k is read from the effect.
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "gpu_helpers.h"
#include "method_lookup.h"
#include "renderer/effect_files.h"
#include "renderer/oit/wboit_msaa.h"
#include "renderer/translucency.h"

namespace rhi_test {
namespace {

using renderer::Translucency;
using renderer::TranslucencySettings;
using renderer::oit::MethodInfo;

constexpr uint32_t kWidth = 64, kHeight = 36;

struct Rgb {
  double r, g, b;
  double& operator[](int c) { return c == 0 ? r : c == 1 ? g : b; }
};

// What the frame holds in 8-bit steps, and the samples that made it.
struct MsaaFrame {
  std::vector<uint8_t> frame;
  std::vector<float> opaque, accum, product;  // ((y * w + x) * samples + s) * 4 + c
  uint32_t samples = 0;
};

double Srgb(double linear) {  // IEC 61966-2-1 encode
  linear = std::clamp(linear, 0.0, 1.0);
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
}
double Linear(double srgb) {  // and decode
  srgb = std::clamp(srgb, 0.0, 1.0);
  return srgb <= 0.04045 ? srgb / 12.92 : std::pow((srgb + 0.055) / 1.055, 2.4);
}
double Unorm8(double v) { return std::round(std::clamp(v, 0.0, 1.0) * 255.0); }

// Document 001's formula (2) on one sample or one averaged pixel.
Rgb Weighted(Rgb opaque, const float* accum, float product) {
  if (accum[3] == 0) return opaque;
  const double alpha = 1.0 - product;
  Rgb out{};
  for (int c = 0; c < 3; ++c) out[c] = accum[c] / accum[3] * alpha + opaque[c] * (1 - alpha);
  return out;
}

class WboitMsaaTest : public RhiGpuTest {
 protected:
  MsaaFrame Render(const MethodInfo& method, const TranslucencySettings& settings) {
    std::string error;
    auto t = Translucency::Create(device.Get(), context.Get(), settings, &error);
    EXPECT_NE(t, nullptr) << error;
    if (!t) return {};
    EXPECT_TRUE(t->RenderFrame(method)) << t->error();
    MsaaFrame f;
    f.frame = t->ReadFrame();
    const auto targets = renderer::oit::GetWboitMsaaTargets(*t->MethodInstance(method));
    EXPECT_TRUE(targets.has_value()) << method.name;
    if (!targets) return f;
    f.samples = targets->samples;
    f.opaque = ReadSamples(targets->opaque, kWidth, kHeight, f.samples);
    f.accum = ReadSamples(targets->accum, kWidth, kHeight, f.samples);
    if (targets->product) f.product = ReadSamples(targets->product, kWidth, kHeight, f.samples, "float");
    return f;
  }
  static TranslucencySettings Triangles() {
    TranslucencySettings s;
    s.scene = "triangles";
    s.width = kWidth, s.height = kHeight;
    return s;
  }
  // Every pixel of `f.frame` against `expected(pixel)` (in 8-bit steps) within `tolerance`.
  static void ExpectFrame(const MsaaFrame& f, const std::function<Rgb(size_t pixel)>& expected, double tolerance,
                          const std::string& what) {
    ASSERT_EQ(f.frame.size(), size_t(kWidth) * kHeight * 4);
    int failures = 0;
    for (size_t p = 0; p < size_t(kWidth) * kHeight && failures < 10; ++p) {
      Rgb want = expected(p);
      for (int c = 0; c < 3; ++c)
        if (std::abs(double(f.frame[p * 4 + c]) - want[c]) > tolerance) {
          ADD_FAILURE() << what << ": pixel (" << p % kWidth << "," << p / kWidth << ") channel " << c << " is "
                        << int(f.frame[p * 4 + c]) << ", the CPU model " << want[c];
          ++failures;
        }
    }
  }
};

size_t Index(const MsaaFrame& f, size_t pixel, uint32_t sample) { return (pixel * f.samples + sample) * 4; }

Rgb OpaqueSample(const MsaaFrame& f, size_t pixel, uint32_t s) {
  const float* o = &f.opaque[Index(f, pixel, s)];
  return {o[0], o[1], o[2]};
}

// The resolve of a UNORM target: the average of the samples' stored 8-bit values.
Rgb ResolveUnorm(const MsaaFrame& f, const std::function<Rgb(uint32_t sample)>& composite) {
  Rgb sum{};
  for (uint32_t s = 0; s < f.samples; ++s) {
    Rgb c = composite(s);
    for (int k = 0; k < 3; ++k) sum[k] += Unorm8(c[k]);
  }
  for (int k = 0; k < 3; ++k) sum[k] /= f.samples;
  return sum;
}

// wboit-msaa: formula (2) per sample, each stored in 8 bits, then the samples averaged.
TEST_F(WboitMsaaTest, PerSampleCompositeEqualsTheCpuModel) {
  const MsaaFrame f = Render(Method("wboit-msaa"), Triangles());
  ASSERT_EQ(f.samples, renderer::oit::kDefaultMsaaSamples);
  ASSERT_FALSE(f.product.empty());
  ExpectFrame(
      f,
      [&](size_t p) {
        return ResolveUnorm(f, [&](uint32_t s) {
          return Weighted(OpaqueSample(f, p, s), &f.accum[Index(f, p, s)], f.product[Index(f, p, s)]);
        });
      },
      1.0, "wboit-msaa");
}

// The samples of a pixel averaged first (what ResolveSubresource does to each target).
void Average(const std::vector<float>& v, const MsaaFrame& f, size_t pixel, float out[4]) {
  for (int c = 0; c < 4; ++c) {
    double sum = 0;
    for (uint32_t s = 0; s < f.samples; ++s) sum += v[Index(f, pixel, s) + c];
    out[c] = float(sum / f.samples);
  }
}

// Pixels whose samples all agree in every target: there the per-sample and the
// per-pixel resolve compute the same thing; elsewhere (the triangles' edges) they need not.
bool SamplesAgree(const MsaaFrame& f, size_t p) {
  for (const std::vector<float>* v : {&f.opaque, &f.accum, &f.product})
    for (uint32_t s = 1; s < f.samples; ++s)
      for (int c = 0; c < 4; ++c)
        if ((*v)[Index(f, p, s) + c] != (*v)[Index(f, p, 0) + c]) return false;
  return true;
}

// wboit-msaa-per-pixel: the targets averaged, then formula (2) once. It differs from
// the per-sample resolve on edge pixels (the triangles' edges: some exist) and nowhere
// else: the count of differing pixels is > 0, and every one of them is an edge pixel.
TEST_F(WboitMsaaTest, PerPixelResolveDiffersFromPerSampleOnEdgesOnly) {
  const MsaaFrame perSample = Render(Method("wboit-msaa"), Triangles());
  const MsaaFrame perPixel = Render(Method("wboit-msaa-per-pixel"), Triangles());
  ASSERT_EQ(perPixel.samples, perSample.samples);
  ASSERT_EQ(perPixel.opaque, perSample.opaque) << "the same scene, the same samples";
  ExpectFrame(
      perPixel,
      [&](size_t p) {
        float opaque[4], accum[4], product[4];
        Average(perPixel.opaque, perPixel, p, opaque);
        Average(perPixel.accum, perPixel, p, accum);
        Average(perPixel.product, perPixel, p, product);
        Rgb c = Weighted({opaque[0], opaque[1], opaque[2]}, accum, product[0]);
        return Rgb{Unorm8(c.r), Unorm8(c.g), Unorm8(c.b)};
      },
      1.0, "wboit-msaa-per-pixel");

  size_t edges = 0, differingEdges = 0, differingInteriors = 0;
  for (size_t p = 0; p < size_t(kWidth) * kHeight; ++p) {
    const bool edge = !SamplesAgree(perSample, p);
    const bool differs = !std::equal(&perSample.frame[p * 4], &perSample.frame[p * 4 + 3], &perPixel.frame[p * 4]);
    edges += edge;
    differingEdges += edge && differs;
    differingInteriors += !edge && differs;
  }
  std::printf("%ux MSAA, %ux%u: %zu edge pixels, %zu of them differ between the resolves; %zu interior pixels differ\n",
              perSample.samples, kWidth, kHeight, edges, differingEdges, differingInteriors);
  EXPECT_GT(differingEdges, 0u) << "of " << edges << " edge pixels";
  EXPECT_EQ(differingInteriors, 0u);
}

// The discussion's variants per sample: C0 + Σ w·c in display values (clamped by the
// UNORM target), with the exposure curve 1 − exp(−k·c), or in linear colour
// written to an sRGB target and resolved in linear space.
struct VariantCase {
  const char* method;
  bool exposure, linear;
};

void PrintTo(const VariantCase& c, std::ostream* os) { *os << c.method; }

class WboitMsaaVariantTest : public WboitMsaaTest, public ::testing::WithParamInterface<VariantCase> {};

TEST_P(WboitMsaaVariantTest, CompositeEqualsTheCpuModel) {
  const VariantCase v = GetParam();
  const MethodInfo& method = Method(v.method);
  std::string error;
  auto effect = renderer::oit::LoadMethodEffect(device.Get(), method, nullptr, {}, &error);
  ASSERT_TRUE(effect) << error;
  float k = 0;
  ASSERT_EQ(effect->GetVariableByName("Exposure")->AsScalar()->GetFloat(&k), rhi::S_OK);

  const MsaaFrame f = Render(method, Triangles());
  ASSERT_GT(f.samples, 0u);
  EXPECT_TRUE(f.product.empty()) << "the additive variants keep no product";
  auto sample = [&](size_t p, uint32_t s) {  // C0 + Σ w·c in the blend space, then the curve
    Rgb opaque = OpaqueSample(f, p, s);
    const float* accum = &f.accum[Index(f, p, s)];
    Rgb c{};
    for (int k3 = 0; k3 < 3; ++k3) {
      c[k3] = (v.linear ? Linear(opaque[k3]) : opaque[k3]) + accum[k3];
      if (v.exposure) c[k3] = 1 - std::exp(-double(k) * c[k3]);
    }
    return c;
  };
  ExpectFrame(
      f,
      [&](size_t p) {
        if (!v.linear) return ResolveUnorm(f, [&](uint32_t s) { return sample(p, s); });
        Rgb sum{};  // each sample stored sRGB-encoded in 8 bits, averaged in linear space
        for (uint32_t s = 0; s < f.samples; ++s) {
          Rgb c = sample(p, s);
          for (int k3 = 0; k3 < 3; ++k3) sum[k3] += Linear(Unorm8(Srgb(c[k3])) / 255.0);
        }
        for (int k3 = 0; k3 < 3; ++k3) sum[k3] = Unorm8(Srgb(sum[k3] / f.samples));
        return sum;
      },
      1.0, v.method);
}

INSTANTIATE_TEST_SUITE_P(Document001, WboitMsaaVariantTest,
                         ::testing::Values(VariantCase{"wboit-msaa-additive", false, false},
                                           VariantCase{"wboit-msaa-exposure", true, false},
                                           VariantCase{"wboit-msaa-linear", false, true}),
                         [](const auto& info) {
                           std::string name = info.param.method;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

// The article's failure: the front blue triangle of opacity 1 does not hide the
// green one behind it (formula (2) averages it in), where the exact composite shows
// blue alone. Sampled at the centre of the overlap of blue and green.
TEST_F(WboitMsaaTest, OpacityOneDoesNotHideWhatIsBehind) {
  const MsaaFrame f = Render(Method("wboit-msaa"), Triangles());
  std::string error;
  auto exact = Translucency::Create(device.Get(), context.Get(), Triangles(), &error);
  ASSERT_TRUE(exact) << error;
  ASSERT_TRUE(exact->RenderFrame(Method("prefix-sum"))) << exact->error();
  const std::vector<uint8_t> reference = exact->ReadFrame();
  // Where the exact frame is blue (b > 2 g) the WBOIT frame has more green than it:
  // the green triangle shows through the opaque-looking blue one.
  size_t blue = 0, greener = 0;
  for (size_t p = 0; p < size_t(kWidth) * kHeight; ++p) {
    const uint8_t* e = &reference[p * 4];
    if (e[2] < 100 || e[2] <= 2 * e[1]) continue;
    ++blue;
    greener += f.frame[p * 4 + 1] > e[1] + 20;
  }
  EXPECT_GT(blue, 0u);
  EXPECT_GT(greener, 0u) << "of " << blue << " blue pixels";
}

// 8x where the device has it: refused with the reason where it has not.
TEST_F(WboitMsaaTest, EightSamplesRunOrAreRefusedWithTheReason) {
  TranslucencySettings s = Triangles();
  s.msaaSamples = 8;
  UINT levels = 1;  // the least over document 001's formats
  for (rhi::DXGI_FORMAT format : {rhi::DXGI_FORMAT_R16G16B16A16_FLOAT, rhi::DXGI_FORMAT_R16_FLOAT,
                                  rhi::DXGI_FORMAT_D32_FLOAT, rhi::DXGI_FORMAT_R8G8B8A8_UNORM}) {
    UINT n = 0;
    ASSERT_EQ(device->CheckMultisampleQualityLevels(format, 8, &n), rhi::S_OK);
    levels = std::min(levels, n);
  }
  std::string error;
  auto t = Translucency::Create(device.Get(), context.Get(), s, &error);
  ASSERT_TRUE(t) << error;
  const bool rendered = t->RenderFrame(Method("wboit-msaa"));
  if (levels == 0) {
    EXPECT_FALSE(rendered);
    EXPECT_NE(t->error().find("no 8x multisampled"), std::string::npos) << t->error();
  } else {
    EXPECT_TRUE(rendered) << t->error();
  }
}

}  // namespace
}  // namespace rhi_test
