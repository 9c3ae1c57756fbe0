// Depth buffers read as textures, as depth peeling does: a typeless texture
// with a depth-stencil view and a shader-resource view; a read-only
// depth-stencil view (DSV_READ_ONLY_DEPTH / _STENCIL) depth-tests a pass while
// the same buffer is sampled, its writes dropped; D3D11's hazard rule, which
// unbinds (with a warning) a shader-resource view of a depth buffer bound for
// writing and keeps it beside a read-only view.
#include <cmath>
#include <string>

#include "gpu_helpers.h"

namespace rhi_test {
namespace {

using namespace rhi;

constexpr UINT kW = 8, kH = 8;

struct DepthFormats {
  DXGI_FORMAT typeless, dsv, srv;
  UINT readOnlyFlags;  // every aspect the format has
  const char* name;
};
const DepthFormats kDepthFormats[] = {
    {DXGI_FORMAT_R32_TYPELESS, DXGI_FORMAT_D32_FLOAT, DXGI_FORMAT_R32_FLOAT, DSV_READ_ONLY_DEPTH, "R32_TYPELESS"},
    {DXGI_FORMAT_R24G8_TYPELESS, DXGI_FORMAT_D24_UNORM_S8_UINT, DXGI_FORMAT_R24_UNORM_X8_TYPELESS,
     DSV_READ_ONLY_DEPTH | DSV_READ_ONLY_STENCIL, "R24G8_TYPELESS"},
    {DXGI_FORMAT_R16_TYPELESS, DXGI_FORMAT_D16_UNORM, DXGI_FORMAT_R16_UNORM, DSV_READ_ONLY_DEPTH, "R16_TYPELESS"},
};

// What a depth of `z` reads back as: UNORM depth is stored as round(z * (2^bits - 1)).
float Stored(DXGI_FORMAT dsv, double z) {
  const double steps = dsv == DXGI_FORMAT_D24_UNORM_S8_UINT ? 16777215.0 : dsv == DXGI_FORMAT_D16_UNORM ? 65535.0 : 0;
  return steps ? float(std::round(z * steps) / steps) : float(z);
}

class DepthTextureTest : public RhiGpuTest, public ::testing::WithParamInterface<DepthFormats> {
 protected:
  void SetUp() override {
    RhiGpuTest::SetUp();
    if (HasFatalFailure()) return;
    const DepthFormats& f = GetParam();
    depth_ = MakeTexture(kW, kH, f.typeless, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE);
    ASSERT_TRUE(depth_);
    DEPTH_STENCIL_VIEW_DESC dsv{f.dsv, DSV_DIMENSION_TEXTURE2D, 0, {}};
    ASSERT_EQ(device->CreateDepthStencilView(depth_.Get(), &dsv, writable_.GetAddressOf()), S_OK);
    dsv.Flags = f.readOnlyFlags;
    ASSERT_EQ(device->CreateDepthStencilView(depth_.Get(), &dsv, readOnly_.GetAddressOf()), S_OK);
    SHADER_RESOURCE_VIEW_DESC srv{};
    srv.Format = f.srv;
    srv.ViewDimension = SRV_DIMENSION_TEXTURE2D;
    srv.Texture2D = {0, 1};
    ASSERT_EQ(device->CreateShaderResourceView(depth_.Get(), &srv, srv_.GetAddressOf()), S_OK);
    out_ = MakeRenderTarget(kW, kH, DXGI_FORMAT_R32_FLOAT);
    sampleDepth_ = PS(R"(Texture2D<float> D : register(t0);
        float4 main(float4 pos : SV_Position) : SV_Target { return D.Load(int3(pos.xy, 0)).xxxx; })");
  }
  // The opaque pass: depth 0.25 in columns 0-3, 0.75 in 4-5, the clear 1.0 in 6-7.
  void DrawOpaqueDepth() {
    BindTarget(nullptr, kW, kH, writable_.Get());
    context->ClearDepthStencilView(writable_.Get(), CLEAR_DEPTH | CLEAR_STENCIL, 1.0f, 0);
    UseColorPipeline();
    context->PSSetShader(nullptr, nullptr, 0);  // depth only
    DrawVertices(Quad(0, 0, 4, kH, kRed, kW, kH, 0.25f));
    DrawVertices(Quad(4, 0, 6, kH, kRed, kW, kH, 0.75f));
    context->OMSetRenderTargets(0, nullptr, nullptr);
  }
  // A full-target quad at depth `z` whose pixel shader writes the depth it samples into out_.
  void DrawSamplingQuad(float z) {
    UseColorPipeline();
    context->PSSetShader(sampleDepth_.Get(), nullptr, 0);
    DrawVertices(Quad(0, 0, kW, kH, kWhite, kW, kH, z));
  }
  // One row of out_ (every row is the same).
  std::vector<float> OutRow() {
    std::vector<float> all = ReadFloats(out_.texture.Get());
    for (UINT y = 1; y < kH; ++y)
      for (UINT x = 0; x < kW; ++x) EXPECT_EQ(all[y * kW + x], all[x]) << "row " << y << " differs at " << x;
    return {all.begin(), all.begin() + kW};
  }
  void BindSrv() {
    ShaderResourceView* srvs[] = {srv_.Get()};
    context->PSSetShaderResources(0, 1, srvs);
  }
  float Depth(double z) const { return Stored(GetParam().dsv, z); }

  ComPtr<Texture2D> depth_;
  ComPtr<DepthStencilView> writable_, readOnly_;
  ComPtr<ShaderResourceView> srv_;
  Target out_;
  ComPtr<PixelShader> sampleDepth_;
};

// The depth-peeling pass: the opaque depth is tested (LESS) through a read-only
// view while the pixel shader samples the same buffer. Where the quad at 0.5
// is behind the opaque depth (columns 0-3) nothing is written; elsewhere the
// sampled depth is. The pass's depth state writes depth (DEPTH_WRITE_MASK_ALL),
// and D3D11 drops those writes: sampled afterwards, the buffer is unchanged.
TEST_P(DepthTextureTest, ReadOnlyViewDepthTestsWhileTheSameBufferIsSampled) {
  DrawOpaqueDepth();
  BindSrv();  // bound before the read-only view: binding that view leaves it bound
  BindTarget(out_.rtv.Get(), kW, kH, readOnly_.Get());
  Clear(out_.rtv.Get(), {-1, -1, -1, -1});
  DrawSamplingQuad(0.5f);
  const std::vector<float> peeled = OutRow();
  for (UINT x = 0; x < kW; ++x) {
    const float expected = x < 4 ? -1.0f : x < 6 ? Depth(0.75) : 1.0f;
    EXPECT_EQ(peeled[x], expected) << "column " << x;
  }
  EXPECT_TRUE(Refusals().empty()) << Refusals().front();

  BindTarget(out_.rtv.Get(), kW, kH);  // no depth buffer: the quad covers every pixel
  BindSrv();
  Clear(out_.rtv.Get(), {-1, -1, -1, -1});
  DrawSamplingQuad(0.5f);
  const std::vector<float> after = OutRow();
  for (UINT x = 0; x < kW; ++x) {
    const float expected = x < 4 ? Depth(0.25) : x < 6 ? Depth(0.75) : 1.0f;
    EXPECT_EQ(after[x], expected) << "column " << x << ": a write through the read-only view was not dropped";
  }
}

// D3D11's hazard rule with depth: a writable depth-stencil view and a
// shader-resource view of the same buffer are never bound together. Binding
// the writable view unbinds the SRV; binding the SRV while it is bound binds
// NULL; both say so. A NULL SRV reads 0.
TEST_P(DepthTextureTest, WritableViewAndShaderResourceViewAreNeverBoundTogether) {
  DrawOpaqueDepth();
  BindSrv();
  ClearMessages();
  BindTarget(out_.rtv.Get(), kW, kH, writable_.Get());
  EXPECT_TRUE(RefusedWith("OMSetRenderTargets: the resource being bound for output is still bound on input; "
                          "forcing PS shader resource slot 0 to NULL"));
  BindTarget(out_.rtv.Get(), kW, kH);
  DrawSamplingQuad(0.5f);
  EXPECT_EQ(OutRow(), std::vector<float>(kW, 0.0f)) << "the SRV was still bound";

  BindTarget(out_.rtv.Get(), kW, kH, writable_.Get());
  ClearMessages();
  BindSrv();
  EXPECT_TRUE(RefusedWith("PSSetShaderResources: the resource of shader resource slot 0 is still bound on output; "
                          "forcing it to NULL"));
  BindTarget(out_.rtv.Get(), kW, kH);
  DrawSamplingQuad(0.5f);
  EXPECT_EQ(OutRow(), std::vector<float>(kW, 0.0f)) << "the SRV was bound beside a writable view";

  // With the read-only view the same binding holds, in either order.
  BindTarget(out_.rtv.Get(), kW, kH, readOnly_.Get());
  ClearMessages();
  BindSrv();
  EXPECT_TRUE(Refusals().empty()) << Refusals().front();
  DEPTH_STENCIL_DESC always;
  always.DepthFunc = COMPARISON_ALWAYS;
  ComPtr<DepthStencilState> state = DepthStencil(always);
  context->OMSetDepthStencilState(state.Get(), 0);
  DrawSamplingQuad(0.5f);
  const std::vector<float> sampled = OutRow();
  for (UINT x = 0; x < kW; ++x)
    EXPECT_EQ(sampled[x], x < 4 ? Depth(0.25) : x < 6 ? Depth(0.75) : 1.0f) << "column " << x;
}

INSTANTIATE_TEST_SUITE_P(Formats, DepthTextureTest, ::testing::ValuesIn(kDepthFormats),
                         [](const auto& info) { return std::string(info.param.name); });

// A multisampled depth buffer read per sample through Texture2DMS<float>.
TEST_F(RhiGpuTest, MultisampledDepthIsReadPerSampleThroughTexture2DMS) {
  UINT levels = 0;
  ASSERT_EQ(device->CheckMultisampleQualityLevels(DXGI_FORMAT_D32_FLOAT, 4, &levels), S_OK);
  ASSERT_EQ(levels, 1u) << "Vulkan guarantees 4 samples for depth attachments";
  ComPtr<Texture2D> depth = MakeTexture(kW, kH, DXGI_FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE, 4);
  DEPTH_STENCIL_VIEW_DESC dsvDesc{DXGI_FORMAT_D32_FLOAT, DSV_DIMENSION_TEXTURE2DMS, 0, {}};
  ComPtr<DepthStencilView> dsv;
  ASSERT_EQ(device->CreateDepthStencilView(depth.Get(), &dsvDesc, dsv.GetAddressOf()), S_OK);
  SHADER_RESOURCE_VIEW_DESC srvDesc{};
  srvDesc.Format = DXGI_FORMAT_R32_FLOAT;
  srvDesc.ViewDimension = SRV_DIMENSION_TEXTURE2DMS;
  ComPtr<ShaderResourceView> srv;
  ASSERT_EQ(device->CreateShaderResourceView(depth.Get(), &srvDesc, srv.GetAddressOf()), S_OK);
  BindTarget(nullptr, kW, kH, dsv.Get());
  context->ClearDepthStencilView(dsv.Get(), CLEAR_DEPTH, 1.0f, 0);
  UseColorPipeline();
  context->PSSetShader(nullptr, nullptr, 0);  // depth only
  DrawVertices(Quad(0, 0, 3, kH, kRed, kW, kH, 0.375f));
  const std::vector<float> samples = ReadSamples(srv.Get(), kW, kH, 4, "float");
  for (UINT y = 0; y < kH; ++y)
    for (UINT x = 0; x < kW; ++x)
      for (UINT s = 0; s < 4; ++s)
        EXPECT_EQ(samples[((y * kW + x) * 4 + s) * 4], x < 3 ? 0.375f : 1.0f)
            << "pixel (" << x << "," << y << ") sample " << s;
}

// The stencil of an R24G8 texture read through X24_TYPELESS_G8_UINT: D3D11
// returns it in G (Vulkan reads it in R; the view swizzles). The hazard rule
// holds per aspect: a view that only makes depth read-only still writes
// stencil, so it unbinds a stencil SRV and keeps a depth SRV.
TEST_F(RhiGpuTest, StencilIsReadInGreenAndTheHazardRuleHoldsPerAspect) {
  ComPtr<Texture2D> texture =
      MakeTexture(kW, kH, DXGI_FORMAT_R24G8_TYPELESS, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE);
  DEPTH_STENCIL_VIEW_DESC dsvDesc{DXGI_FORMAT_D24_UNORM_S8_UINT, DSV_DIMENSION_TEXTURE2D, 0, {}};
  ComPtr<DepthStencilView> writable, depthReadOnly;
  ASSERT_EQ(device->CreateDepthStencilView(texture.Get(), &dsvDesc, writable.GetAddressOf()), S_OK);
  dsvDesc.Flags = DSV_READ_ONLY_DEPTH;
  ASSERT_EQ(device->CreateDepthStencilView(texture.Get(), &dsvDesc, depthReadOnly.GetAddressOf()), S_OK);
  SHADER_RESOURCE_VIEW_DESC srvDesc{};
  srvDesc.ViewDimension = SRV_DIMENSION_TEXTURE2D;
  srvDesc.Texture2D = {0, 1};
  srvDesc.Format = DXGI_FORMAT_R24_UNORM_X8_TYPELESS;
  ComPtr<ShaderResourceView> depthSrv, stencilSrv;
  ASSERT_EQ(device->CreateShaderResourceView(texture.Get(), &srvDesc, depthSrv.GetAddressOf()), S_OK);
  srvDesc.Format = DXGI_FORMAT_X24_TYPELESS_G8_UINT;
  ASSERT_EQ(device->CreateShaderResourceView(texture.Get(), &srvDesc, stencilSrv.GetAddressOf()), S_OK);

  // Stencil 7 in columns 0-3, the clear 0 elsewhere.
  BindTarget(nullptr, kW, kH, writable.Get());
  context->ClearDepthStencilView(writable.Get(), CLEAR_DEPTH | CLEAR_STENCIL, 1.0f, 0);
  DEPTH_STENCIL_DESC replace;
  replace.DepthEnable = FALSE;
  replace.StencilEnable = TRUE;
  replace.FrontFace.StencilPassOp = replace.BackFace.StencilPassOp = STENCIL_OP_REPLACE;
  ComPtr<DepthStencilState> state = DepthStencil(replace);
  context->OMSetDepthStencilState(state.Get(), 7);
  UseColorPipeline();
  context->PSSetShader(nullptr, nullptr, 0);
  DrawVertices(Quad(0, 0, 4, kH, kRed, kW, kH));
  context->OMSetDepthStencilState(nullptr, 0);

  Target out = MakeRenderTarget(kW, kH, DXGI_FORMAT_R32G32B32A32_FLOAT);
  BindTarget(out.rtv.Get(), kW, kH);
  ShaderResourceView* srvs[] = {depthSrv.Get(), stencilSrv.Get()};
  context->PSSetShaderResources(0, 2, srvs);
  ComPtr<PixelShader> ps = PS(R"(Texture2D<float> D : register(t0); Texture2D<uint4> S : register(t1);
      float4 main(float4 pos : SV_Position) : SV_Target {
        uint4 s = S.Load(int3(pos.xy, 0));
        return float4(D.Load(int3(pos.xy, 0)), s.r, s.g, s.a); })");
  DrawFullScreen(ps.Get());
  std::vector<float> texels = ReadFloats(out.texture.Get());
  for (UINT x = 0; x < kW; ++x) {
    const float* t = &texels[(3 * kW + x) * 4];
    EXPECT_EQ(t[0], 1.0f) << "depth, column " << x;
    EXPECT_EQ(t[1], 0.0f) << "R of the stencil view, column " << x;
    EXPECT_EQ(t[2], x < 4 ? 7.0f : 0.0f) << "stencil (G), column " << x;
    EXPECT_EQ(t[3], 1.0f) << "A of the stencil view, column " << x;
  }

  ClearMessages();
  BindTarget(out.rtv.Get(), kW, kH, depthReadOnly.Get());
  EXPECT_TRUE(RefusedWith("forcing PS shader resource slot 1 to NULL"));
  EXPECT_FALSE(RefusedWith("forcing PS shader resource slot 0 to NULL")) << "the depth SRV reads a read-only aspect";
  EXPECT_EQ(Refusals().size(), 1u);
}

TEST_F(RhiGpuTest, DepthAsTextureRulesAreEnforcedWithReason) {
  // D3D11: a depth format is never a shader resource; the typeless family is.
  TEXTURE2D_DESC desc{4, 4, 1, 1, DXGI_FORMAT_D32_FLOAT, {1, 0}, USAGE_DEFAULT,
                      BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE, 0, 0};
  ComPtr<Texture2D> texture;
  EXPECT_EQ(device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("BIND_SHADER_RESOURCE cannot use DXGI_FORMAT_D32_FLOAT"));
  desc.Format = DXGI_FORMAT_R32_TYPELESS;
  ASSERT_EQ(device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()), S_OK);
  SHADER_RESOURCE_VIEW_DESC srv{};
  srv.Format = DXGI_FORMAT_D32_FLOAT;
  srv.ViewDimension = SRV_DIMENSION_TEXTURE2D;
  srv.Texture2D = {0, 1};
  ComPtr<ShaderResourceView> view;
  EXPECT_EQ(device->CreateShaderResourceView(texture.Get(), &srv, view.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("DXGI_FORMAT_D32_FLOAT cannot be the format of this kind of view"));
  DEPTH_STENCIL_VIEW_DESC dsv{DXGI_FORMAT_D32_FLOAT, DSV_DIMENSION_TEXTURE2D, DSV_READ_ONLY_STENCIL, {}};
  ComPtr<DepthStencilView> depthView;
  EXPECT_EQ(device->CreateDepthStencilView(texture.Get(), &dsv, depthView.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("DSV_READ_ONLY_STENCIL needs a format with stencil; DXGI_FORMAT_D32_FLOAT has none"));
  ComPtr<Texture2D> unsampled = MakeTexture(4, 4, DXGI_FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL);
  srv.Format = DXGI_FORMAT_R32_FLOAT;
  EXPECT_EQ(device->CreateShaderResourceView(unsampled.Get(), &srv, view.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("CreateShaderResourceView: the texture lacks BIND_SHADER_RESOURCE"));
}

}  // namespace
}  // namespace rhi_test
