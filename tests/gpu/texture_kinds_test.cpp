// Cube maps (RESOURCE_MISC_TEXTURECUBE: faces rendered through array-slice
// render-target views, read through TextureCube and TextureCubeArray views),
// GenerateMips (RESOURCE_MISC_GENERATE_MIPS) and SetResourceMinLOD
// (RESOURCE_MISC_RESOURCE_CLAMP), with D3D11's refusals.
#include "gpu_helpers.h"

namespace rhi_test {
namespace {

using namespace rhi;

// One exact colour per face (+X, -X, +Y, -Y, +Z, -Z of D3D11's face order).
const Color kFaceColors[6] = {kRed, kGreen, kBlue, kWhite, {1, 1, 0, 1}, {0, 1, 1, 1}};
const uint32_t kFacePixels[6] = {kRedPx, kGreenPx, kBluePx, kWhitePx, RGBA(255, 255, 0, 255), RGBA(0, 255, 255, 255)};


// A square R8G8B8A8_UNORM texture's desc, single-sampled.
TEXTURE2D_DESC SquareRgba8(UINT size, UINT mipLevels, UINT arraySize, UINT bindFlags, UINT miscFlags) {
  TEXTURE2D_DESC desc{};
  desc.Width = desc.Height = size;
  desc.MipLevels = mipLevels;
  desc.ArraySize = arraySize;
  desc.Format = DXGI_FORMAT_R8G8B8A8_UNORM;
  desc.SampleDesc = {1, 0};
  desc.BindFlags = bindFlags;
  desc.MiscFlags = miscFlags;
  return desc;
}
class TextureKindsTest : public RhiGpuTest {
 protected:
  static TEXTURE2D_DESC CubeDesc(UINT size, UINT cubes) {
    TEXTURE2D_DESC desc = SquareRgba8(size, 1, 6 * cubes, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE, RESOURCE_MISC_TEXTURECUBE);
    return desc;
  }

  // Draws `color` over slice `slice` of `cube` through a one-slice TEXTURE2DARRAY render-target view.
  void RenderFace(Texture2D* cube, UINT slice, UINT size, Color color) {
    RENDER_TARGET_VIEW_DESC desc{};
    desc.Format = DXGI_FORMAT_R8G8B8A8_UNORM;
    desc.ViewDimension = RTV_DIMENSION_TEXTURE2DARRAY;
    desc.Texture2DArray = {0, slice, 1};
    ComPtr<RenderTargetView> rtv;
    ASSERT_EQ(device->CreateRenderTargetView(cube, &desc, rtv.GetAddressOf()), S_OK);
    Clear(rtv.Get(), kBlack);
    BindTarget(rtv.Get(), size, size);
    UseColorPipeline();
    DrawVertices(Quad(0, 0, float(size), float(size), color, size, size));
  }

  // Samples `srv` along the six face directions into pixels 0..5 of a 6x1 target: `declaration`
  // declares the view at t0, `sample` samples it along `dir` with `point_`.
  std::vector<uint8_t> SampleFaces(ShaderResourceView* srv, const char* declaration, const char* sample) {
    const std::string ps = std::string(declaration) + R"(
      SamplerState point_ : register(s0);
      float4 main(float4 pos : SV_Position) : SV_Target {
        const float3 dirs[6] = {float3(1, 0, 0), float3(-1, 0, 0), float3(0, 1, 0),
                                float3(0, -1, 0), float3(0, 0, 1), float3(0, 0, -1)};
        float3 dir = dirs[uint(pos.x)];
        return )" + sample + R"(;
      })";
    context->ClearState();
    Target target = MakeRenderTarget(6, 1);
    BindTarget(target.rtv.Get(), 6, 1);
    context->PSSetShaderResources(0, 1, &srv);
    ComPtr<SamplerState> sampler = PointSampler();
    SamplerState* samplers[] = {sampler.Get()};
    context->PSSetSamplers(0, 1, samplers);
    ComPtr<PixelShader> shader = PS(ps);
    DrawFullScreen(shader.Get());
    return ReadTexture(target.texture.Get());
  }
};

TEST_F(TextureKindsTest, CubeFacesRenderedThroughArraySliceViewsAreSampledThroughTextureCube) {
  const TEXTURE2D_DESC desc = CubeDesc(4, 1);
  ComPtr<Texture2D> cube;
  ASSERT_EQ(device->CreateTexture2D(&desc, nullptr, cube.GetAddressOf()), S_OK);
  for (UINT face = 0; face < 6; ++face) RenderFace(cube.Get(), face, 4, kFaceColors[face]);
  for (UINT face = 0; face < 6; ++face) {
    SCOPED_TRACE(testing::Message() << "face " << face);
    EXPECT_EQ(CountPixels(ReadTexture(cube.Get(), face), kFacePixels[face]), 16) << "the RTV wrote its slice only";
  }
  // A NULL desc on a cube texture is a TEXTURECUBE view (D3D11's default).
  ComPtr<ShaderResourceView> srv;
  ASSERT_EQ(device->CreateShaderResourceView(cube.Get(), nullptr, srv.GetAddressOf()), S_OK);
  SHADER_RESOURCE_VIEW_DESC got;
  srv->GetDesc(&got);
  EXPECT_EQ(got.ViewDimension, SRV_DIMENSION_TEXTURECUBE);
  const std::vector<uint8_t> pixels =
      SampleFaces(srv.Get(), "TextureCube<float4> cube : register(t0);", "cube.SampleLevel(point_, dir, 0)");
  for (UINT face = 0; face < 6; ++face) EXPECT_EQ(Pixel(pixels, 6, face, 0), kFacePixels[face]) << "face " << face;
}

TEST_F(TextureKindsTest, TextureCubeArrayViewSelectsTheCubeByIndex) {
  // Two cubes; the second's faces get the colours rotated by one, so the cube index shows.
  const TEXTURE2D_DESC desc = CubeDesc(2, 2);
  ComPtr<Texture2D> cubes;
  ASSERT_EQ(device->CreateTexture2D(&desc, nullptr, cubes.GetAddressOf()), S_OK);
  for (UINT slice = 0; slice < 12; ++slice)
    RenderFace(cubes.Get(), slice, 2, kFaceColors[slice < 6 ? slice : (slice + 1) % 6]);
  SHADER_RESOURCE_VIEW_DESC view{};
  view.Format = DXGI_FORMAT_R8G8B8A8_UNORM;
  view.ViewDimension = SRV_DIMENSION_TEXTURECUBEARRAY;
  view.TextureCubeArray = {0, 1, 0, 2};
  ComPtr<ShaderResourceView> srv;
  ASSERT_EQ(device->CreateShaderResourceView(cubes.Get(), &view, srv.GetAddressOf()), S_OK);
  const std::vector<uint8_t> pixels = SampleFaces(srv.Get(), "TextureCubeArray<float4> cubes : register(t0);",
                                                  "cubes.SampleLevel(point_, float4(dir, 1), 0)");
  for (UINT face = 0; face < 6; ++face)
    EXPECT_EQ(Pixel(pixels, 6, face, 0), kFacePixels[(face + 1) % 6]) << "face " << face << " of cube 1";
}

TEST_F(TextureKindsTest, CubeRulesAreD3D11s) {
  TEXTURE2D_DESC desc = CubeDesc(4, 1);
  desc.ArraySize = 4;
  ComPtr<Texture2D> texture;
  EXPECT_EQ(device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("ArraySize a multiple of 6"));
  desc = CubeDesc(4, 1);
  desc.Height = 2;
  EXPECT_EQ(device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("square faces"));
  // A cube view of a texture created without RESOURCE_MISC_TEXTURECUBE.
  desc = CubeDesc(4, 1);
  desc.MiscFlags = 0;
  ASSERT_EQ(device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()), S_OK);
  SHADER_RESOURCE_VIEW_DESC view{};
  view.Format = DXGI_FORMAT_R8G8B8A8_UNORM;
  view.ViewDimension = SRV_DIMENSION_TEXTURECUBE;
  view.TextureCube = {0, 1};
  ComPtr<ShaderResourceView> srv;
  EXPECT_EQ(device->CreateShaderResourceView(texture.Get(), &view, srv.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("RESOURCE_MISC_TEXTURECUBE"));
}

TEST_F(TextureKindsTest, GenerateMipsFillsEachLevelWithTheBoxFilterOfTheOneAbove) {
  TEXTURE2D_DESC desc = SquareRgba8(4, 3, 1, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE, RESOURCE_MISC_GENERATE_MIPS);
  ComPtr<Texture2D> texture;
  ASSERT_EQ(device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()), S_OK);
  // Red values per 2x2 block with means 90, 250, 26, 62 (their mean: 107). Every pair along
  // either axis has an even sum, so the box filter is exact whether the device's linear
  // filter rounds after each lerp (llvmpipe's 8-bit filtering does) or only at the end.
  const uint8_t red[4][4] = {{0, 100, 250, 250}, {200, 60, 250, 250}, {10, 20, 40, 40}, {30, 44, 84, 84}};
  std::vector<uint32_t> level0(16);
  for (UINT y = 0; y < 4; ++y)
    for (UINT x = 0; x < 4; ++x) level0[y * 4 + x] = RGBA(red[y][x], 0, 0, 255);
  context->UpdateSubresource(texture.Get(), 0, nullptr, level0.data(), 16, 0);
  ComPtr<ShaderResourceView> srv;
  ASSERT_EQ(device->CreateShaderResourceView(texture.Get(), nullptr, srv.GetAddressOf()), S_OK);
  context->GenerateMips(srv.Get());
  const std::vector<uint8_t> level1 = ReadTexture(texture.Get(), 1), level2 = ReadTexture(texture.Get(), 2);
  EXPECT_EQ(Pixel(level1, 2, 0, 0), RGBA(90, 0, 0, 255));
  EXPECT_EQ(Pixel(level1, 2, 1, 0), RGBA(250, 0, 0, 255));
  EXPECT_EQ(Pixel(level1, 2, 0, 1), RGBA(26, 0, 0, 255));
  EXPECT_EQ(Pixel(level1, 2, 1, 1), RGBA(62, 0, 0, 255));
  EXPECT_EQ(Pixel(level2, 1, 0, 0), RGBA(107, 0, 0, 255));
}

TEST_F(TextureKindsTest, GenerateMipsRulesAreD3D11s) {
  TEXTURE2D_DESC desc = SquareRgba8(4, 0, 1, BIND_SHADER_RESOURCE, RESOURCE_MISC_GENERATE_MIPS);
  ComPtr<Texture2D> texture;
  EXPECT_EQ(device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("RESOURCE_MISC_GENERATE_MIPS needs BIND_SHADER_RESOURCE and BIND_RENDER_TARGET"));
  // GenerateMips on a view of a texture without the flag is reported and ignored.
  desc.MiscFlags = 0;
  ASSERT_EQ(device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()), S_OK);
  ComPtr<ShaderResourceView> srv;
  ASSERT_EQ(device->CreateShaderResourceView(texture.Get(), nullptr, srv.GetAddressOf()), S_OK);
  ClearMessages();
  context->GenerateMips(srv.Get());
  EXPECT_TRUE(RefusedWith("GenerateMips: the view's resource must be a texture created with RESOURCE_MISC_GENERATE_MIPS"));
}

// A 4x4 texture of 3 mips, each one colour (red, green, blue), with RESOURCE_MISC_RESOURCE_CLAMP.
class ResourceMinLodTest : public TextureKindsTest {
 protected:
  void SetUp() override {
    TextureKindsTest::SetUp();
    if (HasFatalFailure()) return;
    TEXTURE2D_DESC desc = SquareRgba8(4, 3, 1, BIND_SHADER_RESOURCE, RESOURCE_MISC_RESOURCE_CLAMP);
    const std::vector<uint32_t> mip0(16, kRedPx), mip1(4, kGreenPx), mip2(1, kBluePx);
    const SUBRESOURCE_DATA data[3] = {{mip0.data(), 16, 0}, {mip1.data(), 8, 0}, {mip2.data(), 4, 0}};
    ASSERT_EQ(device->CreateTexture2D(&desc, data, texture.GetAddressOf()), S_OK);
    ASSERT_EQ(device->CreateShaderResourceView(texture.Get(), nullptr, srv.GetAddressOf()), S_OK);
  }

  // The colour `srv` samples at LOD 0 (SampleLevel with a point sampler).
  uint32_t SampleAtLod0() {
    Target target = MakeRenderTarget(1, 1);
    BindTarget(target.rtv.Get(), 1, 1);
    ComPtr<SamplerState> sampler = PointSampler();
    context->PSSetSamplers(0, 1, sampler.GetAddressOf());
    context->PSSetShaderResources(0, 1, srv.GetAddressOf());
    if (!ps_)
      ps_ = PS(R"(Texture2D<float4> t : register(t0);
        SamplerState s : register(s0);
        float4 main(float4 pos : SV_Position) : SV_Target { return t.SampleLevel(s, float2(0.5, 0.5), 0); })");
    DrawFullScreen(ps_.Get());
    return Pixel(ReadTexture(target.texture.Get()), 1, 0, 0);
  }

  ComPtr<Texture2D> texture;
  ComPtr<ShaderResourceView> srv;
  ComPtr<PixelShader> ps_;
};

TEST_F(ResourceMinLodTest, SampledLodIsClampedToTheResourceMinimum) {
  EXPECT_EQ(context->GetResourceMinLOD(texture.Get()), 0.0f) << "the default";
  EXPECT_EQ(SampleAtLod0(), kRedPx);
  context->SetResourceMinLOD(texture.Get(), 2.0f);
  EXPECT_EQ(context->GetResourceMinLOD(texture.Get()), 2.0f);
  EXPECT_EQ(SampleAtLod0(), kBluePx) << "LOD 0 clamped to mip 2";
  context->SetResourceMinLOD(texture.Get(), 1.0f);
  EXPECT_EQ(SampleAtLod0(), kGreenPx);
  // A view whose levels all lie below the clamp reads 0 (D3D11: an empty set is out of bounds).
  SHADER_RESOURCE_VIEW_DESC first{};
  first.Format = DXGI_FORMAT_R8G8B8A8_UNORM;
  first.ViewDimension = SRV_DIMENSION_TEXTURE2D;
  first.Texture2D = {0, 1};
  ASSERT_EQ(device->CreateShaderResourceView(texture.Get(), &first, srv.ReleaseAndGetAddressOf()), S_OK);
  EXPECT_EQ(SampleAtLod0(), 0u);
  context->SetResourceMinLOD(texture.Get(), 0.0f);
  EXPECT_EQ(SampleAtLod0(), kRedPx);
  EXPECT_TRUE(Refusals().empty());
}

// Each clamp value gets its own view variant, a few kept: a clamp moving over many values
// (as texture streaming moves it) samples the right level every time, including values
// whose variant was dropped and made again.
TEST_F(ResourceMinLodTest, EveryClampOfALongChainSamplesItsLevel) {
  TEXTURE2D_DESC desc = SquareRgba8(32, 6, 1, BIND_SHADER_RESOURCE, RESOURCE_MISC_RESOURCE_CLAMP);
  std::vector<std::vector<uint32_t>> levels;
  std::vector<SUBRESOURCE_DATA> data;
  for (UINT mip = 0; mip < 6; ++mip) {
    const UINT size = 32 >> mip;
    levels.emplace_back(size * size, RGBA(40 * mip, 255 - 40 * mip, 0, 255));
    data.push_back({levels.back().data(), size * 4, 0});
  }
  ASSERT_EQ(device->CreateTexture2D(&desc, data.data(), texture.ReleaseAndGetAddressOf()), S_OK);
  ASSERT_EQ(device->CreateShaderResourceView(texture.Get(), nullptr, srv.ReleaseAndGetAddressOf()), S_OK);
  for (UINT minLod : {1, 2, 3, 4, 5, 1, 2, 5, 0}) {
    context->SetResourceMinLOD(texture.Get(), FLOAT(minLod));
    EXPECT_EQ(SampleAtLod0(), RGBA(40 * minLod, 255 - 40 * minLod, 0, 255)) << "MinLOD " << minLod;
  }
  EXPECT_TRUE(Refusals().empty());
}

TEST_F(ResourceMinLodTest, DeferredContextsRecordTheClamp) {
  ComPtr<DeviceContext> deferred;
  ASSERT_EQ(device->CreateDeferredContext(0, deferred.GetAddressOf()), S_OK);
  deferred->SetResourceMinLOD(texture.Get(), 2.0f);
  EXPECT_EQ(context->GetResourceMinLOD(texture.Get()), 0.0f) << "recorded, not yet executed";
  ComPtr<CommandList> list;
  ASSERT_EQ(deferred->FinishCommandList(FALSE, list.GetAddressOf()), S_OK);
  context->ExecuteCommandList(list.Get(), FALSE);
  EXPECT_EQ(context->GetResourceMinLOD(texture.Get()), 2.0f);
  EXPECT_EQ(deferred->GetResourceMinLOD(texture.Get()), 2.0f);
  EXPECT_EQ(SampleAtLod0(), kBluePx);
}

TEST_F(ResourceMinLodTest, RulesAreD3D11s) {
  context->SetResourceMinLOD(texture.Get(), 3.5f);
  EXPECT_TRUE(RefusedWith("SetResourceMinLOD: MinLOD 3.5"));
  context->SetResourceMinLOD(texture.Get(), -1.0f);
  EXPECT_EQ(context->GetResourceMinLOD(texture.Get()), 0.0f) << "refused calls change nothing";
  ComPtr<Texture2D> unclamped = MakeTexture(4, 4, DXGI_FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE);
  ClearMessages();
  context->SetResourceMinLOD(unclamped.Get(), 1.0f);
  EXPECT_TRUE(RefusedWith("the texture was not created with RESOURCE_MISC_RESOURCE_CLAMP"));
  EXPECT_EQ(context->GetResourceMinLOD(unclamped.Get()), 0.0f);
  const uint32_t zero = 0;
  ComPtr<Buffer> buffer = MakeBuffer(BIND_SHADER_RESOURCE, &zero, 4);
  ClearMessages();
  context->SetResourceMinLOD(buffer.Get(), 0.0f);
  EXPECT_TRUE(RefusedWith("pResource must be a texture"));
  EXPECT_EQ(context->GetResourceMinLOD(buffer.Get()), 0.0f);
}

}  // namespace
}  // namespace rhi_test
