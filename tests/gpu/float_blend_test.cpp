// BLEND_OP_MIN / BLEND_OP_MAX on 32-bit float targets, as dual depth peeling
// uses them: every fragment writes (-z, z) and MAX keeps (-nearest, farthest).
// D3D11 ignores the blend factors of MIN and MAX, so the tests set them to
// ZERO: a backend that applied them would store zeros. Expected values are
// folded on the CPU from the quads below, exactly (the depths are exact floats).
#include <algorithm>
#include <string>
#include <tuple>

#include "gpu_helpers.h"

namespace rhi_test {
namespace {

using namespace rhi;

constexpr UINT kW = 8, kH = 8;

// Overlapping quads [x0,x1) x [y0,y1) at depth z, drawn in this order.
struct DepthQuad {
  float x0, y0, x1, y1, z;
};
constexpr DepthQuad kQuads[] = {
    {0, 0, 6, 8, 0.5f}, {2, 0, 8, 8, 0.25f}, {0, 0, 8, 4, 0.75f}, {3, 2, 5, 6, 0.125f}, {6, 5, 8, 8, 0.875f},
};

struct FormatCase {
  DXGI_FORMAT format;
  const char* name;
  UINT channels;
};
using BlendParam = std::tuple<FormatCase, BLEND_OP, UINT>;

class FloatBlendTest : public RhiGpuTest, public ::testing::WithParamInterface<BlendParam> {
 protected:
  const FormatCase& format() const { return std::get<0>(GetParam()); }
  BLEND_OP op() const { return std::get<1>(GetParam()); }
  UINT samples() const { return std::get<2>(GetParam()); }

  // The value a channel holds after every quad: the clear value folded with
  // each covering quad's output, -z in red and z in green.
  float Expected(UINT x, UINT y, UINT channel, float clear) const {
    float value = clear;
    for (const DepthQuad& q : kQuads) {
      if (float(x) + 0.5f < q.x0 || float(x) + 0.5f >= q.x1 || float(y) + 0.5f < q.y0 || float(y) + 0.5f >= q.y1)
        continue;
      const float out = channel == 0 ? -q.z : q.z;
      value = op() == BLEND_OP_MAX ? std::max(value, out) : std::min(value, out);
    }
    return value;
  }
};

TEST_P(FloatBlendTest, MinMaxIgnoreTheFactorsAndKeepTheExtremeOfEveryFragment) {
  UINT levels = 0;
  ASSERT_EQ(device->CheckMultisampleQualityLevels(format().format, samples(), &levels), S_OK);
  if (!levels) GTEST_SKIP() << "no " << samples() << "x target of this format on " << device->GetAdapterName();
  Target target = MakeRenderTarget(kW, kH, format().format, samples());
  const float clear = op() == BLEND_OP_MAX ? -2.0f : 2.0f;
  Clear(target.rtv.Get(), {clear, clear, clear, clear});
  BLEND_DESC desc;
  RENDER_TARGET_BLEND_DESC& rt = desc.RenderTarget[0];
  rt.BlendEnable = TRUE;
  rt.BlendOp = rt.BlendOpAlpha = op();
  rt.SrcBlend = rt.DestBlend = rt.SrcBlendAlpha = rt.DestBlendAlpha = BLEND_ZERO;  // ignored by MIN and MAX
  ComPtr<BlendState> blend = Blend(desc);
  context->OMSetBlendState(blend.Get(), nullptr, DEFAULT_SAMPLE_MASK);
  UseColorPipeline();
  ComPtr<PixelShader> ps =
      PS("float4 main(float4 pos : SV_Position) : SV_Target { return float4(-pos.z, pos.z, 0, 1); }");
  context->PSSetShader(ps.Get(), nullptr, 0);
  BindTarget(target.rtv.Get(), kW, kH);
  for (const DepthQuad& q : kQuads) DrawVertices(Quad(q.x0, q.y0, q.x1, q.y1, kWhite, kW, kH, q.z));
  EXPECT_TRUE(Refusals().empty()) << Refusals().front();
  // Every sample of a pixel holds the same value (the quads cover whole pixels): the resolve keeps it.
  const std::vector<float> texels = ReadFloats(target.texture.Get());
  ASSERT_EQ(texels.size(), size_t(kW) * kH * format().channels);
  for (UINT y = 0; y < kH; ++y)
    for (UINT x = 0; x < kW; ++x)
      for (UINT c = 0; c < format().channels; ++c)
        EXPECT_EQ(texels[(y * kW + x) * format().channels + c], Expected(x, y, c, clear))
            << "pixel (" << x << "," << y << ") channel " << c;
}

INSTANTIATE_TEST_SUITE_P(
    DepthPeelingTargets, FloatBlendTest,
    ::testing::Combine(::testing::Values(FormatCase{DXGI_FORMAT_R32_FLOAT, "R32_FLOAT", 1},
                                         FormatCase{DXGI_FORMAT_R32G32_FLOAT, "R32G32_FLOAT", 2}),
                       ::testing::Values(BLEND_OP_MIN, BLEND_OP_MAX), ::testing::Values(1u, 4u)),
    [](const ::testing::TestParamInfo<BlendParam>& info) {
      return std::string(std::get<0>(info.param).name) + (std::get<1>(info.param) == BLEND_OP_MAX ? "_Max" : "_Min") +
             "_x" + std::to_string(std::get<2>(info.param));
    });

}  // namespace
}  // namespace rhi_test
