// Buffer creation rules, Map / UpdateSubresource / Copy paths, texture kinds and
// render-target formats, each checked against exact bytes.
#include <cstring>

#include "gpu_helpers.h"
#include "rhi/capture.h"

namespace rhi_test {
namespace {

using namespace rhi;

class ResourceTest : public RhiGpuTest {
 protected:
  ComPtr<Texture2D> Texture(UINT width, UINT height, DXGI_FORMAT format, const void* data, UINT rowPitch,
                            UINT mipLevels = 1, UINT arraySize = 1, const SUBRESOURCE_DATA* init = nullptr) {
    TEXTURE2D_DESC desc{};
    desc.Width = width;
    desc.Height = height;
    desc.MipLevels = mipLevels;
    desc.ArraySize = arraySize;
    desc.Format = format;
    desc.SampleDesc.Count = 1;
    desc.Usage = USAGE_DEFAULT;
    desc.BindFlags = BIND_SHADER_RESOURCE;
    SUBRESOURCE_DATA one{data, rowPitch, rowPitch * height};
    if (!init && data) init = &one;
    ComPtr<Texture2D> texture;
    EXPECT_EQ(device->CreateTexture2D(&desc, init, texture.GetAddressOf()), S_OK);
    return texture;
  }
  ComPtr<ShaderResourceView> SRV(Resource* resource, const SHADER_RESOURCE_VIEW_DESC* desc = nullptr) {
    ComPtr<ShaderResourceView> view;
    EXPECT_EQ(device->CreateShaderResourceView(resource, desc, view.GetAddressOf()), S_OK);
    return view;
  }
  // Draws a full-target triangle with `ps` into `rtv` (width x height).
  void FullScreen(RenderTargetView* rtv, UINT width, UINT height, PixelShader* ps) {
    if (!fullScreenVS_)
      fullScreenVS_ = VS(R"(float4 main(uint id : SV_VertexID) : SV_Position {
          return float4(float(id & 1) * 4 - 1, 1 - float(id & 2) * 2, 0.5, 1); })");
    BindTarget(rtv, width, height);
    context->IASetInputLayout(nullptr);
    context->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    context->VSSetShader(fullScreenVS_.Get(), nullptr, 0);
    context->PSSetShader(ps, nullptr, 0);
    context->Draw(3, 0);
  }
  ComPtr<VertexShader> fullScreenVS_;
};

// ---------------------------------------------------------------------------
// Buffers

TEST_F(ResourceTest, CreateBufferRefusesInvalidDescriptionsWithReason) {
  struct Case {
    BUFFER_DESC desc;
    const char* fragment;
  };
  const Case cases[] = {
      {{16, USAGE_IMMUTABLE, BIND_VERTEX_BUFFER, 0, 0, 0}, "USAGE_IMMUTABLE"},             // no initial data
      {{20, USAGE_DEFAULT, BIND_CONSTANT_BUFFER, 0, 0, 0}, "multiple of 16"},              // constant buffer size
      {{16, USAGE_STAGING, BIND_VERTEX_BUFFER, CPU_ACCESS_READ, 0, 0}, "USAGE_STAGING"},   // staging with bind flags
      {{16, USAGE_DYNAMIC, BIND_VERTEX_BUFFER, 0, 0, 0}, "CPU_ACCESS_WRITE"},              // dynamic without CPU write
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.fragment);
    ClearMessages();
    ComPtr<Buffer> buffer;
    EXPECT_EQ(device->CreateBuffer(&c.desc, nullptr, buffer.GetAddressOf()), E_INVALIDARG);
    EXPECT_FALSE(buffer);
    EXPECT_TRUE(RefusedWith(c.fragment)) << (Refusals().empty() ? "no refusal message" : Refusals().back());
  }
}

// D3D11.0: a fully typed texture is viewed only in its own format; a typeless one
// in any member of its family (here UNORM and UNORM_SRGB of R8G8B8A8_TYPELESS,
// the same bytes read linear and decoded).
TEST_F(ResourceTest, ViewFormatsFollowTheTypelessFamilyRule) {
  TEXTURE2D_DESC desc{4, 4, 1, 1, DXGI_FORMAT_R8G8B8A8_UNORM, {1, 0}, USAGE_DEFAULT,
                      BIND_SHADER_RESOURCE | BIND_RENDER_TARGET, 0, 0};
  ComPtr<Texture2D> typed;
  ASSERT_EQ(device->CreateTexture2D(&desc, nullptr, typed.GetAddressOf()), S_OK);
  SHADER_RESOURCE_VIEW_DESC srgb{};
  srgb.Format = DXGI_FORMAT_R8G8B8A8_UNORM_SRGB;
  srgb.ViewDimension = SRV_DIMENSION_TEXTURE2D;
  srgb.Texture2D = {0, 1};
  ComPtr<ShaderResourceView> view;
  EXPECT_EQ(device->CreateShaderResourceView(typed.Get(), &srgb, view.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("cannot view a resource of format DXGI_FORMAT_R8G8B8A8_UNORM"))
      << (Refusals().empty() ? "no refusal message" : Refusals().back());

  desc.Format = DXGI_FORMAT_R8G8B8A8_TYPELESS;
  ComPtr<Texture2D> typeless;
  ASSERT_EQ(device->CreateTexture2D(&desc, nullptr, typeless.GetAddressOf()), S_OK);
  RENDER_TARGET_VIEW_DESC linear{};
  linear.Format = DXGI_FORMAT_R8G8B8A8_UNORM;
  linear.ViewDimension = RTV_DIMENSION_TEXTURE2D;
  ComPtr<RenderTargetView> rtv;
  ASSERT_EQ(device->CreateRenderTargetView(typeless.Get(), &linear, rtv.GetAddressOf()), S_OK);
  ASSERT_EQ(device->CreateShaderResourceView(typeless.Get(), &srgb, view.ReleaseAndGetAddressOf()), S_OK);
  const FLOAT half[4] = {0.5f, 0.5f, 0.5f, 1.0f};  // stored as code 128 (127.5 rounds either way, FS 3.2.3.6)
  context->ClearRenderTargetView(rtv.Get(), half);
  Target out = MakeRenderTarget(4, 4, DXGI_FORMAT_R32G32B32A32_FLOAT);
  auto ps = PS(R"(Texture2D t : register(t0);
                  float4 main(float4 pos : SV_Position) : SV_Target { return t.Load(int3(pos.xy, 0)); })");
  ShaderResourceView* srvs[] = {view.Get()};
  context->PSSetShaderResources(0, 1, srvs);
  FullScreen(out.rtv.Get(), 4, 4, ps.Get());
  const std::vector<float> texels = [&] {
    std::vector<uint8_t> bytes = ReadTexture(out.texture.Get());
    std::vector<float> f(bytes.size() / 4);
    std::memcpy(f.data(), bytes.data(), bytes.size());
    return f;
  }();
  // sRGB decode of code 127 or 128: 0.2122 or 0.2159 (not the linear 0.5).
  EXPECT_NEAR(texels[0], 0.214f, 0.003f);
  EXPECT_FLOAT_EQ(texels[3], 1.0f);
}

TEST_F(ResourceTest, MapWriteDiscardOnDynamicConstantBufferGivesEachDrawItsOwnValue) {
  // Three draws between three WRITE_DISCARD maps of one constant buffer: each
  // draw must see the value mapped before it (the buffer is renamed), not the last.
  Target target = MakeRenderTarget(8, 8);
  BindTarget(target.rtv.Get(), 8, 8);
  Clear(target.rtv.Get(), kBlack);
  UseColorPipeline();
  auto ps = PS(R"(cbuffer C : register(b0) { float4 color; };
                  float4 main(float4 pos : SV_Position) : SV_Target { return color; })");
  context->PSSetShader(ps.Get(), nullptr, 0);
  ComPtr<Buffer> cb = MakeBuffer(BIND_CONSTANT_BUFFER, nullptr, 16, USAGE_DYNAMIC);
  Buffer* cbs[] = {cb.Get()};
  context->PSSetConstantBuffers(0, 1, cbs);
  std::vector<Vertex> v = Quad(0, 0, 3, 8, kBlack, 8, 8);
  for (auto q : {Quad(3, 0, 6, 8, kBlack, 8, 8), Quad(6, 0, 8, 8, kBlack, 8, 8)}) v.insert(v.end(), q.begin(), q.end());
  ComPtr<Buffer> vb = VertexBuffer(v);
  const UINT stride = sizeof(Vertex), offset = 0;
  Buffer* vbs[] = {vb.Get()};
  context->IASetVertexBuffers(0, 1, vbs, &stride, &offset);
  const Color colors[] = {kRed, kGreen, kBlue};
  for (UINT i = 0; i < 3; ++i) {
    MAPPED_SUBRESOURCE mapped{};
    ASSERT_EQ(context->Map(cb.Get(), 0, MAP_WRITE_DISCARD, 0, &mapped), S_OK);
    std::memcpy(mapped.pData, &colors[i], 16);
    context->Unmap(cb.Get(), 0);
    context->Draw(6, 6 * i);
  }
  EXPECT_EQ(Picture(ReadTexture(target.texture.Get()), 8, 8, kLegend), Rows(8, "RRRGGGBB"));
}

TEST_F(ResourceTest, MapWriteNoOverwriteOnDynamicVertexBufferKeepsEarlierVertices) {
  Target target = MakeRenderTarget(8, 8);
  BindTarget(target.rtv.Get(), 8, 8);
  Clear(target.rtv.Get(), kBlack);
  UseColorPipeline();
  ComPtr<Buffer> vb = MakeBuffer(BIND_VERTEX_BUFFER, nullptr, 12 * sizeof(Vertex), USAGE_DYNAMIC);
  const UINT stride = sizeof(Vertex), offset = 0;
  Buffer* vbs[] = {vb.Get()};
  context->IASetVertexBuffers(0, 1, vbs, &stride, &offset);
  // Vertices 0..5: red columns 0-3 (DISCARD); 6..11: green columns 4-7 (NO_OVERWRITE).
  MAPPED_SUBRESOURCE mapped{};
  ASSERT_EQ(context->Map(vb.Get(), 0, MAP_WRITE_DISCARD, 0, &mapped), S_OK);
  std::memcpy(mapped.pData, Quad(0, 0, 4, 8, kRed, 8, 8).data(), 6 * sizeof(Vertex));
  context->Unmap(vb.Get(), 0);
  context->Draw(6, 0);
  ASSERT_EQ(context->Map(vb.Get(), 0, MAP_WRITE_NO_OVERWRITE, 0, &mapped), S_OK);
  std::memcpy(static_cast<Vertex*>(mapped.pData) + 6, Quad(4, 0, 8, 8, kGreen, 8, 8).data(), 6 * sizeof(Vertex));
  context->Unmap(vb.Get(), 0);
  context->Draw(6, 6);
  EXPECT_EQ(Picture(ReadTexture(target.texture.Get()), 8, 8, kLegend), Rows(8, "RRRRGGGG"));
  // NO_OVERWRITE kept vertices 0..5: one draw of all 12 gives the same picture.
  Clear(target.rtv.Get(), kBlack);
  context->Draw(12, 0);
  EXPECT_EQ(Picture(ReadTexture(target.texture.Get()), 8, 8, kLegend), Rows(8, "RRRRGGGG"));
}

TEST_F(ResourceTest, MapReadOnStagingBufferAfterCopyResourceReturnsTheBytes) {
  const uint32_t words[8] = {1, 2, 3, 0xFFFFFFFF, 0x80000000, 0x12345678, 0, 42};
  ComPtr<Buffer> source = MakeBuffer(BIND_VERTEX_BUFFER, words, sizeof words);
  BUFFER_DESC desc{sizeof words, USAGE_STAGING, 0, CPU_ACCESS_READ, 0, 0};
  ComPtr<Buffer> staging;
  ASSERT_EQ(device->CreateBuffer(&desc, nullptr, staging.GetAddressOf()), S_OK);
  context->CopyResource(staging.Get(), source.Get());
  MAPPED_SUBRESOURCE mapped{};
  ASSERT_EQ(context->Map(staging.Get(), 0, MAP_READ, 0, &mapped), S_OK);
  ASSERT_NE(mapped.pData, nullptr);
  EXPECT_EQ(std::memcmp(mapped.pData, words, sizeof words), 0);
  context->Unmap(staging.Get(), 0);
}

TEST_F(ResourceTest, CopyResourceCopiesBufferToBuffer) {
  const uint32_t words[4] = {0xCAFEF00D, 7, 8, 9};
  const uint32_t zeros[4] = {};
  ComPtr<Buffer> source = MakeBuffer(BIND_SHADER_RESOURCE, words, sizeof words);
  ComPtr<Buffer> dest = MakeBuffer(BIND_VERTEX_BUFFER, zeros, sizeof zeros);
  context->CopyResource(dest.Get(), source.Get());
  EXPECT_EQ(ReadBufferAs<uint32_t>(dest.Get()), (std::vector<uint32_t>{0xCAFEF00D, 7, 8, 9}));
}

TEST_F(ResourceTest, UpdateSubresourceOnDefaultBufferWritesOnlyTheBox) {
  std::vector<uint32_t> initial(8, 0xAAAAAAAAu);
  ComPtr<Buffer> buffer = MakeBuffer(BIND_VERTEX_BUFFER, initial.data(), 32);
  const uint32_t update[3] = {1, 2, 3};
  const BOX box{8, 0, 0, 20, 1, 1};  // bytes [8, 20): words 2, 3, 4
  context->UpdateSubresource(buffer.Get(), 0, &box, update, 0, 0);
  EXPECT_EQ(ReadBufferAs<uint32_t>(buffer.Get()),
            (std::vector<uint32_t>{0xAAAAAAAA, 0xAAAAAAAA, 1, 2, 3, 0xAAAAAAAA, 0xAAAAAAAA, 0xAAAAAAAA}));
}

// ---------------------------------------------------------------------------
// Texture copies and updates

// rhi::CaptureTexture2D (the readback of the tests, the demos and the screenshots):
// rows come back tightly packed whatever the staging row pitch (3 texels of R8_UNORM
// are 3 bytes a row), a mip level has that level's size, and what it cannot read
// is refused with the reason.
TEST_F(ResourceTest, CaptureTexture2DPacksRowsAndRefusesWhatItCannotRead) {
  const uint8_t bytes[3 * 2] = {1, 2, 3, 4, 5, 6};
  ComPtr<Texture2D> narrow = Texture(3, 2, DXGI_FORMAT_R8_UNORM, bytes, 3);
  std::vector<uint8_t> texels;
  ASSERT_EQ(CaptureTexture2D(device.Get(), context.Get(), narrow.Get(), 0, &texels), S_OK);
  EXPECT_EQ(texels, std::vector<uint8_t>(std::begin(bytes), std::end(bytes)));

  const uint32_t level0[16] = {}, level1[4] = {0x01020304, 0x05060708, 0x090A0B0C, 0x0D0E0F10};
  const SUBRESOURCE_DATA levels[2] = {{level0, 16, 64}, {level1, 8, 16}};
  ComPtr<Texture2D> mipped = Texture(4, 4, DXGI_FORMAT_R8G8B8A8_UNORM, nullptr, 0, 2, 1, levels);
  ASSERT_EQ(CaptureTexture2D(device.Get(), context.Get(), mipped.Get(), 1, &texels), S_OK);
  EXPECT_EQ(texels.size(), 16u);
  EXPECT_EQ(Pixel(texels, 2, 1, 1), 0x0D0E0F10u);

  EXPECT_EQ(CaptureTexture2D(device.Get(), context.Get(), mipped.Get(), 2, &texels), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("CaptureTexture2D: subresource 2 is out of range (2 subresources)"));
  // A multisampled texture is resolved first; an integer one has no resolve.
  TEXTURE2D_DESC msDesc{4, 4, 1, 1, DXGI_FORMAT_R8G8B8A8_UINT, {4, 0}, USAGE_DEFAULT, BIND_RENDER_TARGET, 0, 0};
  ComPtr<Texture2D> multisampled;
  ASSERT_EQ(device->CreateTexture2D(&msDesc, nullptr, multisampled.GetAddressOf()), S_OK);
  EXPECT_EQ(CaptureTexture2D(device.Get(), context.Get(), multisampled.Get(), 0, &texels), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("the texture is multisampled (SampleDesc.Count 4) and DXGI_FORMAT_R8G8B8A8_UINT is an "
                          "integer format, which has no resolve"));
}

TEST_F(ResourceTest, UpdateSubresourceOnTextureRegionHonoursBoxAndSourceRowPitch) {
  std::vector<uint32_t> zeros(64, 0);
  ComPtr<Texture2D> texture = Texture(8, 8, DXGI_FORMAT_R8G8B8A8_UNORM, zeros.data(), 32);
  // A 3x2 region at (2,3); source rows are 4 pixels apart (16 bytes), the 4th unused.
  const uint32_t source[8] = {0x11, 0x12, 0x13, 0xBAD, 0x21, 0x22, 0x23, 0xBAD};
  const BOX box{2, 3, 0, 5, 5, 1};
  context->UpdateSubresource(texture.Get(), 0, &box, source, 16, 32);
  std::vector<uint8_t> pixels = ReadTexture(texture.Get());
  for (UINT y = 0; y < 8; ++y)
    for (UINT x = 0; x < 8; ++x) {
      uint32_t expected = 0;
      if (x >= 2 && x < 5 && y >= 3 && y < 5) expected = source[(y - 3) * 4 + (x - 2)];
      EXPECT_EQ(Pixel(pixels, 8, x, y), expected) << "pixel " << x << "," << y;
    }
}

TEST_F(ResourceTest, CopySubresourceRegionCopiesTextureBoxToDestinationOffset) {
  std::vector<uint32_t> pattern(64), zeros(64, 0);
  for (UINT y = 0; y < 8; ++y)
    for (UINT x = 0; x < 8; ++x) pattern[y * 8 + x] = RGBA(x * 16, y * 16, 7, 255);
  ComPtr<Texture2D> source = Texture(8, 8, DXGI_FORMAT_R8G8B8A8_UNORM, pattern.data(), 32);
  ComPtr<Texture2D> dest = Texture(8, 8, DXGI_FORMAT_R8G8B8A8_UNORM, zeros.data(), 32);
  const BOX box{1, 2, 0, 4, 5, 1};  // source pixels x 1..3, y 2..4
  context->CopySubresourceRegion(dest.Get(), 0, 5, 0, 0, source.Get(), 0, &box);
  std::vector<uint8_t> pixels = ReadTexture(dest.Get());
  for (UINT y = 0; y < 8; ++y)
    for (UINT x = 0; x < 8; ++x) {
      uint32_t expected = 0;
      if (x >= 5 && y < 3) expected = pattern[(y + 2) * 8 + (x - 5 + 1)];
      EXPECT_EQ(Pixel(pixels, 8, x, y), expected) << "pixel " << x << "," << y;
    }
}

// ---------------------------------------------------------------------------
// Sampling texture kinds (point sampler: the texel containing the coordinate)

TEST_F(ResourceTest, SampleLevelWithPointSamplerReadsTheRequestedMipOfInitialData) {
  // 4x4 with 3 mips: mip 0 all red, mip 1 = {red, green / blue, white}, mip 2 green.
  std::vector<uint32_t> mip0(16, kRedPx);
  const uint32_t mip1[4] = {kRedPx, kGreenPx, kBluePx, kWhitePx};
  const uint32_t mip2[1] = {kGreenPx};
  const SUBRESOURCE_DATA init[3] = {{mip0.data(), 16, 64}, {mip1, 8, 16}, {mip2, 4, 4}};
  ComPtr<Texture2D> texture = Texture(4, 4, DXGI_FORMAT_R8G8B8A8_UNORM, nullptr, 0, 3, 1, init);
  auto srv = SRV(texture.Get());
  auto sampler = PointSampler();
  // A 2x2 target: pixel centres at uv (0.25 | 0.75, 0.25 | 0.75).
  auto ps = PS(R"(Texture2D t : register(t0); SamplerState s : register(s0);
                  cbuffer C : register(b0) { float lod; };
                  float4 main(float4 pos : SV_Position) : SV_Target { return t.SampleLevel(s, pos.xy / 2, lod); })");
  ComPtr<Buffer> cb = MakeBuffer(BIND_CONSTANT_BUFFER, nullptr, 16);
  ShaderResourceView* srvs[] = {srv.Get()};
  SamplerState* samplers[] = {sampler.Get()};
  Buffer* cbs[] = {cb.Get()};
  context->PSSetShaderResources(0, 1, srvs);
  context->PSSetSamplers(0, 1, samplers);
  context->PSSetConstantBuffers(0, 1, cbs);
  Target target = MakeRenderTarget(2, 2);
  const std::vector<std::pair<float, std::vector<std::string>>> cases = {
      {0.0f, {"RR", "RR"}}, {1.0f, {"RG", "BW"}}, {2.0f, {"GG", "GG"}}};
  for (const auto& [lod, expected] : cases) {
    SCOPED_TRACE(testing::Message() << "lod " << lod);
    const float constants[4] = {lod, 0, 0, 0};
    context->UpdateSubresource(cb.Get(), 0, nullptr, constants, 0, 0);
    Clear(target.rtv.Get(), kBlack);
    FullScreen(target.rtv.Get(), 2, 2, ps.Get());
    EXPECT_EQ(Picture(ReadTexture(target.texture.Get()), 2, 2, kLegend), expected);
  }
}

TEST_F(ResourceTest, Texture1DIsSampledAlongU) {
  const uint32_t texels[4] = {kRedPx, kGreenPx, kBluePx, kWhitePx};
  TEXTURE1D_DESC desc{4, 1, 1, DXGI_FORMAT_R8G8B8A8_UNORM, USAGE_IMMUTABLE, BIND_SHADER_RESOURCE, 0, 0};
  const SUBRESOURCE_DATA init{texels, 0, 0};
  ComPtr<Texture1D> texture;
  ASSERT_EQ(device->CreateTexture1D(&desc, &init, texture.GetAddressOf()), S_OK);
  auto srv = SRV(texture.Get());
  auto sampler = PointSampler();
  auto ps = PS(R"(Texture1D t : register(t0); SamplerState s : register(s0);
                  float4 main(float4 pos : SV_Position) : SV_Target { return t.SampleLevel(s, pos.x / 4, 0); })");
  ShaderResourceView* srvs[] = {srv.Get()};
  SamplerState* samplers[] = {sampler.Get()};
  context->PSSetShaderResources(0, 1, srvs);
  context->PSSetSamplers(0, 1, samplers);
  Target target = MakeRenderTarget(4, 1);
  FullScreen(target.rtv.Get(), 4, 1, ps.Get());
  EXPECT_EQ(Picture(ReadTexture(target.texture.Get()), 4, 1, kLegend), std::vector<std::string>{"RGBW"});
}

TEST_F(ResourceTest, Texture2DArraySamplesTheSliceSelectedByTheThirdCoordinate) {
  // Slices 0, 1, 2 are uniformly red, green, blue. Pixel x of a 3x1 target
  // samples slice x. A view of slices 1..2 maps slice 0 to 1 and clamps 2 to its last (2).
  std::vector<uint32_t> red(4, kRedPx), green(4, kGreenPx), blue(4, kBluePx);
  const SUBRESOURCE_DATA init[3] = {{red.data(), 8, 16}, {green.data(), 8, 16}, {blue.data(), 8, 16}};
  ComPtr<Texture2D> texture = Texture(2, 2, DXGI_FORMAT_R8G8B8A8_UNORM, nullptr, 0, 1, 3, init);
  auto all = SRV(texture.Get());
  SHADER_RESOURCE_VIEW_DESC desc{};
  desc.Format = DXGI_FORMAT_R8G8B8A8_UNORM;
  desc.ViewDimension = SRV_DIMENSION_TEXTURE2DARRAY;
  desc.Texture2DArray = {0, 1, 1, 2};
  auto lastTwo = SRV(texture.Get(), &desc);
  auto sampler = PointSampler();
  auto ps = PS(R"(Texture2DArray t : register(t0); SamplerState s : register(s0);
                  float4 main(float4 pos : SV_Position) : SV_Target {
                    return t.SampleLevel(s, float3(0.5, 0.5, floor(pos.x)), 0); })");
  SamplerState* samplers[] = {sampler.Get()};
  context->PSSetSamplers(0, 1, samplers);
  Target target = MakeRenderTarget(3, 1);
  for (const auto& [view, expected] : {std::pair{all.Get(), "RGB"}, std::pair{lastTwo.Get(), "GBB"}}) {
    ShaderResourceView* srvs[] = {view};
    context->PSSetShaderResources(0, 1, srvs);
    FullScreen(target.rtv.Get(), 3, 1, ps.Get());
    EXPECT_EQ(Picture(ReadTexture(target.texture.Get()), 3, 1, kLegend), std::vector<std::string>{expected});
  }
}

// ---------------------------------------------------------------------------
// Render-target formats

TEST_F(ResourceTest, R32UintTargetIsClearedAndWrittenWithExactIntegers) {
  // D3D11 clears integer targets with the float value converted to an integer: 7.0 -> 7.
  Target target = MakeRenderTarget(8, 8, DXGI_FORMAT_R32_UINT);
  BindTarget(target.rtv.Get(), 8, 8);
  const FLOAT clear[4] = {7, 0, 0, 0};
  context->ClearRenderTargetView(target.rtv.Get(), clear);
  UseColorPipeline();
  auto ps = PS("uint main(float4 pos : SV_Position) : SV_Target { return 0xDEADBEEF; }");
  context->PSSetShader(ps.Get(), nullptr, 0);
  DrawVertices(Quad(0, 0, 4, 8, kBlack, 8, 8));
  std::vector<uint8_t> pixels = ReadTexture(target.texture.Get());
  for (UINT y = 0; y < 8; ++y)
    for (UINT x = 0; x < 8; ++x)
      EXPECT_EQ(Pixel(pixels, 8, x, y), x < 4 ? 0xDEADBEEFu : 7u) << "pixel " << x << "," << y;
}

TEST_F(ResourceTest, R16G16B16A16FloatTargetHoldsExactHalfValues) {
  // Clear (0.25, -1, 2, 0.5) -> halves 0x3400 0xBC00 0x4000 0x3800; the draw in
  // columns 0-1 writes (1, 0.5, -2, 65504) -> 0x3C00 0x3800 0xC000 0x7BFF.
  Target target = MakeRenderTarget(4, 4, DXGI_FORMAT_R16G16B16A16_FLOAT);
  BindTarget(target.rtv.Get(), 4, 4);
  Clear(target.rtv.Get(), {0.25f, -1, 2, 0.5f});
  UseColorPipeline();
  DrawVertices(Quad(0, 0, 2, 4, {1, 0.5f, -2, 65504}, 4, 4));
  std::vector<uint8_t> bytes = ReadTexture(target.texture.Get());
  ASSERT_GE(bytes.size(), 4u * 4 * 8);
  auto halves = [&](UINT x, UINT y) {
    std::vector<uint16_t> h(4);
    std::memcpy(h.data(), bytes.data() + (y * 4 + x) * 8, 8);
    return h;
  };
  for (UINT y = 0; y < 4; ++y)
    for (UINT x = 0; x < 4; ++x)
      EXPECT_EQ(halves(x, y), x < 2 ? (std::vector<uint16_t>{0x3C00, 0x3800, 0xC000, 0x7BFF})
                                    : (std::vector<uint16_t>{0x3400, 0xBC00, 0x4000, 0x3800}))
          << "pixel " << x << "," << y;
}

TEST_F(ResourceTest, B8G8R8X8ShaderResourceReadsAlphaAsOne) {
  // Texels stored as bytes B=0x10 G=0x20 R=0x30 X=0x00; sampling gives
  // (0x30, 0x20, 0x10)/255 and alpha 1, written to RGBA8 as (0x30, 0x20, 0x10, 0xFF).
  const uint8_t texel[4] = {0x10, 0x20, 0x30, 0x00};
  std::vector<uint8_t> data;
  for (int i = 0; i < 4; ++i) data.insert(data.end(), texel, texel + 4);
  ComPtr<Texture2D> texture = Texture(2, 2, DXGI_FORMAT_B8G8R8X8_UNORM, data.data(), 8);
  auto srv = SRV(texture.Get());
  ShaderResourceView* srvs[] = {srv.Get()};
  context->PSSetShaderResources(0, 1, srvs);
  auto ps = PS(R"(Texture2D t : register(t0);
                  float4 main(float4 pos : SV_Position) : SV_Target { return t.Load(int3(pos.xy, 0)); })");
  Target target = MakeRenderTarget(2, 2);
  FullScreen(target.rtv.Get(), 2, 2, ps.Get());
  EXPECT_EQ(CountPixels(ReadTexture(target.texture.Get()), RGBA(0x30, 0x20, 0x10, 0xFF)), 4);
}

TEST_F(ResourceTest, B8G8R8X8TargetBlendsWithDestAlphaOne) {
  // Cleared to (0,0,0,0): the X channel still reads as alpha 1. With
  // src * DEST_ALPHA + dst * INV_DEST_ALPHA the result is the source,
  // (1, 0.25, 0.75) -> R 255, G 64, B 191 (bytes B, G, R); alpha 0 would leave 0.
  Target target = MakeRenderTarget(8, 8, DXGI_FORMAT_B8G8R8X8_UNORM);
  BindTarget(target.rtv.Get(), 8, 8);
  Clear(target.rtv.Get(), {0, 0, 0, 0});
  UseColorPipeline();
  BLEND_DESC desc;
  desc.RenderTarget[0].BlendEnable = TRUE;
  desc.RenderTarget[0].SrcBlend = BLEND_DEST_ALPHA;
  desc.RenderTarget[0].DestBlend = BLEND_INV_DEST_ALPHA;
  auto state = Blend(desc);
  context->OMSetBlendState(state.Get(), nullptr, DEFAULT_SAMPLE_MASK);
  DrawVertices(Quad(0, 0, 8, 8, {1, 0.25f, 0.75f, 0}, 8, 8));
  std::vector<uint8_t> bytes = ReadTexture(target.texture.Get());
  ASSERT_EQ(bytes.size(), 8u * 8 * 4);
  for (UINT i = 0; i < 64; ++i) {
    ASSERT_EQ(bytes[i * 4 + 0], 191) << "B of pixel " << i;
    ASSERT_EQ(bytes[i * 4 + 1], 64) << "G of pixel " << i;
    ASSERT_EQ(bytes[i * 4 + 2], 255) << "R of pixel " << i;
  }
}

TEST_F(ResourceTest, D24UnormS8UintDepthStencilTestsDepthAndStencil) {
  // Whether or not the device has D24S8 (the backend may substitute a format),
  // depth 0.5 / stencil 3: red at z 0.25 (LESS passes, stencil 3 == 3) shows,
  // green at z 0.75 fails depth, blue at z 0.25 with reference 4 fails stencil.
  Target target = MakeRenderTarget(8, 8);
  DepthTarget depth = MakeDepthTarget(8, 8, DXGI_FORMAT_D24_UNORM_S8_UINT);
  BindTarget(target.rtv.Get(), 8, 8, depth.dsv.Get());
  Clear(target.rtv.Get(), kBlack);
  context->ClearDepthStencilView(depth.dsv.Get(), CLEAR_DEPTH | CLEAR_STENCIL, 0.5f, 3);
  UseColorPipeline();
  DEPTH_STENCIL_DESC desc;
  desc.StencilEnable = TRUE;
  desc.FrontFace.StencilFunc = COMPARISON_EQUAL;
  desc.BackFace.StencilFunc = COMPARISON_EQUAL;
  auto state = DepthStencil(desc);
  context->OMSetDepthStencilState(state.Get(), 3);
  DrawVertices(Quad(0, 0, 4, 8, kRed, 8, 8, 0.25f));
  DrawVertices(Quad(4, 0, 8, 8, kGreen, 8, 8, 0.75f));
  context->OMSetDepthStencilState(state.Get(), 4);
  DrawVertices(Quad(0, 0, 8, 8, kBlue, 8, 8, 0.25f));
  EXPECT_EQ(Picture(ReadTexture(target.texture.Get()), 8, 8, kLegend), Rows(8, "RRRR...."));
}

}  // namespace
}  // namespace rhi_test
