// 3D (volume) textures: CreateTexture3D's rules, initial data and UpdateSubresource
// with depth pitches, copies of W-slice boxes, staging maps, Texture3D SRVs,
// W-slice render-target views (clears and draws), RWTexture3D UAVs written by a
// compute shader, and GenerateMips. Every expected texel is computed here from
// the values written.
#include <cstring>

#include "gpu_helpers.h"

namespace rhi_test {
namespace {

using namespace rhi;

TEXTURE3D_DESC VolumeDesc(UINT width, UINT height, UINT depth, UINT mips, UINT bindFlags,
                          DXGI_FORMAT format = DXGI_FORMAT_R8G8B8A8_UNORM) {
  TEXTURE3D_DESC desc{};
  desc.Width = width;
  desc.Height = height;
  desc.Depth = depth;
  desc.MipLevels = mips;
  desc.Format = format;
  desc.Usage = USAGE_DEFAULT;
  desc.BindFlags = bindFlags;
  return desc;
}

// The value of texel (x, y, z) of mip `mip` in the tests' RGBA8 volumes: distinct everywhere.
uint32_t TexelValue(UINT mip, UINT x, UINT y, UINT z) { return RGBA(x * 40 + mip, y * 40, z * 40, 255); }

class Texture3DTest : public RhiGpuTest {
 protected:
  // Every texel of every mip of an RGBA8 volume, mip after mip, slice after slice, row after row
  // (read through a staging copy; checks Map's pitches on the way).
  std::vector<uint32_t> ReadVolume(Texture3D* texture) {
    TEXTURE3D_DESC desc;
    texture->GetDesc(&desc);
    desc.Usage = USAGE_STAGING;
    desc.BindFlags = desc.MiscFlags = 0;
    desc.CPUAccessFlags = CPU_ACCESS_READ;
    ComPtr<Texture3D> staging;
    EXPECT_EQ(device->CreateTexture3D(&desc, nullptr, staging.GetAddressOf()), S_OK);
    if (!staging) return {};
    context->CopyResource(staging.Get(), texture);
    std::vector<uint32_t> texels;
    for (UINT mip = 0; mip < desc.MipLevels; ++mip) {
      const UINT w = std::max(1u, desc.Width >> mip), h = std::max(1u, desc.Height >> mip),
                 d = std::max(1u, desc.Depth >> mip);
      MAPPED_SUBRESOURCE mapped{};
      EXPECT_EQ(context->Map(staging.Get(), mip, MAP_READ, 0, &mapped), S_OK);
      EXPECT_EQ(mapped.RowPitch, w * 4);
      EXPECT_EQ(mapped.DepthPitch, w * h * 4);
      for (UINT z = 0; z < d; ++z)
        for (UINT y = 0; y < h; ++y)
          for (UINT x = 0; x < w; ++x) {
            uint32_t texel;
            std::memcpy(&texel, static_cast<uint8_t*>(mapped.pData) + z * mapped.DepthPitch + y * mapped.RowPitch + x * 4,
                        4);
            texels.push_back(texel);
          }
      context->Unmap(staging.Get(), mip);
    }
    return texels;
  }

  // A volume filled with TexelValue through initial data whose rows and slices are padded
  // (RowPitch and DepthPitch larger than the texels), as D3D11 allows.
  ComPtr<Texture3D> FilledVolume(const TEXTURE3D_DESC& desc) {
    std::vector<std::vector<uint32_t>> levels;
    std::vector<SUBRESOURCE_DATA> data;
    for (UINT mip = 0; mip < desc.MipLevels; ++mip) {
      const UINT w = std::max(1u, desc.Width >> mip), h = std::max(1u, desc.Height >> mip),
                 d = std::max(1u, desc.Depth >> mip);
      const UINT rowTexels = w + 3, sliceTexels = rowTexels * (h + 1);
      std::vector<uint32_t>& level = levels.emplace_back(size_t(sliceTexels) * d, 0xDEADBEEF);
      for (UINT z = 0; z < d; ++z)
        for (UINT y = 0; y < h; ++y)
          for (UINT x = 0; x < w; ++x) level[z * sliceTexels + y * rowTexels + x] = TexelValue(mip, x, y, z);
      data.push_back({level.data(), rowTexels * 4, sliceTexels * 4});
    }
    ComPtr<Texture3D> texture;
    EXPECT_EQ(device->CreateTexture3D(&desc, data.data(), texture.GetAddressOf()), S_OK);
    return texture;
  }

  static std::vector<uint32_t> ExpectedVolume(const TEXTURE3D_DESC& desc) {
    std::vector<uint32_t> texels;
    for (UINT mip = 0; mip < desc.MipLevels; ++mip)
      for (UINT z = 0; z < std::max(1u, desc.Depth >> mip); ++z)
        for (UINT y = 0; y < std::max(1u, desc.Height >> mip); ++y)
          for (UINT x = 0; x < std::max(1u, desc.Width >> mip); ++x) texels.push_back(TexelValue(mip, x, y, z));
    return texels;
  }
};

TEST_F(Texture3DTest, DescTypeAndDefaultViewsAreThoseOfAVolume) {
  const TEXTURE3D_DESC desc =
      VolumeDesc(8, 4, 2, 2, BIND_SHADER_RESOURCE | BIND_RENDER_TARGET | BIND_UNORDERED_ACCESS);
  ComPtr<Texture3D> texture;
  ASSERT_EQ(device->CreateTexture3D(&desc, nullptr, texture.GetAddressOf()), S_OK);
  TEXTURE3D_DESC got;
  texture->GetDesc(&got);
  EXPECT_EQ(std::memcmp(&got, &desc, sizeof desc), 0);
  // MipLevels 0 asks for the full chain, which GetDesc reports: 8x4x2 has 4 levels.
  TEXTURE3D_DESC full = desc;
  full.MipLevels = 0;
  ComPtr<Texture3D> chain;
  ASSERT_EQ(device->CreateTexture3D(&full, nullptr, chain.GetAddressOf()), S_OK);
  chain->GetDesc(&got);
  EXPECT_EQ(got.MipLevels, 4u);
  RESOURCE_DIMENSION dimension;
  texture->GetType(&dimension);
  EXPECT_EQ(dimension, RESOURCE_DIMENSION_TEXTURE3D);
  // NULL descs view the whole resource, as D3D11's defaults.
  ComPtr<ShaderResourceView> srv;
  ASSERT_EQ(device->CreateShaderResourceView(texture.Get(), nullptr, srv.GetAddressOf()), S_OK);
  SHADER_RESOURCE_VIEW_DESC srvDesc;
  srv->GetDesc(&srvDesc);
  EXPECT_EQ(srvDesc.ViewDimension, SRV_DIMENSION_TEXTURE3D);
  EXPECT_EQ(srvDesc.Texture3D.MipLevels, 2u);
  ComPtr<RenderTargetView> rtv;
  ASSERT_EQ(device->CreateRenderTargetView(texture.Get(), nullptr, rtv.GetAddressOf()), S_OK);
  RENDER_TARGET_VIEW_DESC rtvDesc;
  rtv->GetDesc(&rtvDesc);
  EXPECT_EQ(rtvDesc.ViewDimension, RTV_DIMENSION_TEXTURE3D);
  EXPECT_EQ(rtvDesc.Texture3D.WSize, 2u);
  ComPtr<UnorderedAccessView> uav;
  ASSERT_EQ(device->CreateUnorderedAccessView(texture.Get(), nullptr, uav.GetAddressOf()), S_OK);
  UNORDERED_ACCESS_VIEW_DESC uavDesc;
  uav->GetDesc(&uavDesc);
  EXPECT_EQ(uavDesc.ViewDimension, UAV_DIMENSION_TEXTURE3D);
  EXPECT_TRUE(Refusals().empty());
}

// CreateTexture3D's refusals: each desc differs from a valid one in one field.
struct BadVolume {
  const char* name;
  TEXTURE3D_DESC desc;
  const char* reason;
};

TEXTURE3D_DESC With(TEXTURE3D_DESC desc, void (*change)(TEXTURE3D_DESC&)) {
  change(desc);
  return desc;
}

const TEXTURE3D_DESC kValidVolume = VolumeDesc(4, 4, 4, 1, BIND_SHADER_RESOURCE);

std::vector<BadVolume> BadVolumes() {
  return {
      {"zero_depth", With(kValidVolume, [](TEXTURE3D_DESC& d) { d.Depth = 0; }), "size 4x4x0 is outside 1..2048"},
      {"depth_over_2048", With(kValidVolume, [](TEXTURE3D_DESC& d) { d.Depth = 2049; }),
       "size 4x4x2049 is outside 1..2048"},
      {"width_over_2048", With(kValidVolume, [](TEXTURE3D_DESC& d) { d.Width = 4096; }), "outside 1..2048"},
      {"too_many_mips", With(kValidVolume, [](TEXTURE3D_DESC& d) { d.MipLevels = 4; }),
       "MipLevels 4 exceeds the full chain of 3"},
      {"depth_stencil", With(kValidVolume, [](TEXTURE3D_DESC& d) { d.BindFlags |= BIND_DEPTH_STENCIL; }),
       "a 3D texture cannot have BIND_DEPTH_STENCIL"},
      {"depth_format", With(kValidVolume, [](TEXTURE3D_DESC& d) { d.Format = DXGI_FORMAT_D32_FLOAT; d.BindFlags = 0; }),
       "DXGI_FORMAT_D32_FLOAT is a depth format"},
      {"cube", With(kValidVolume, [](TEXTURE3D_DESC& d) { d.MiscFlags = RESOURCE_MISC_TEXTURECUBE; }),
       "RESOURCE_MISC_TEXTURECUBE needs a 2D texture"},
      {"structured", With(kValidVolume, [](TEXTURE3D_DESC& d) { d.MiscFlags = RESOURCE_MISC_BUFFER_STRUCTURED; }),
       "buffer-only flags"},
      {"shared", With(kValidVolume, [](TEXTURE3D_DESC& d) { d.MiscFlags = RESOURCE_MISC_SHARED; }),
       "RESOURCE_MISC_SHARED is not supported"},
      {"mips_without_render_target",
       With(kValidVolume, [](TEXTURE3D_DESC& d) { d.MiscFlags = RESOURCE_MISC_GENERATE_MIPS; }),
       "RESOURCE_MISC_GENERATE_MIPS needs BIND_SHADER_RESOURCE and BIND_RENDER_TARGET"},
      {"vertex_buffer", With(kValidVolume, [](TEXTURE3D_DESC& d) { d.BindFlags |= BIND_VERTEX_BUFFER; }),
       "textures cannot be bound as vertex"},
      {"bc_render_target",
       With(kValidVolume, [](TEXTURE3D_DESC& d) { d.Format = DXGI_FORMAT_BC1_UNORM; d.BindFlags |= BIND_RENDER_TARGET; }),
       "can only have BIND_SHADER_RESOURCE"},
      {"immutable_without_data", With(kValidVolume, [](TEXTURE3D_DESC& d) { d.Usage = USAGE_IMMUTABLE; }),
       "USAGE_IMMUTABLE requires initial data"},
  };
}

class BadVolumeDesc : public Texture3DTest, public testing::WithParamInterface<BadVolume> {};

TEST_P(BadVolumeDesc, IsRefusedWithTheReason) {
  ComPtr<Texture3D> texture;
  EXPECT_EQ(device->CreateTexture3D(&GetParam().desc, nullptr, texture.GetAddressOf()), E_INVALIDARG);
  EXPECT_EQ(texture.Get(), nullptr);
  EXPECT_TRUE(RefusedWith("CreateTexture3D: ")) << "the message names the call";
  EXPECT_TRUE(RefusedWith(GetParam().reason)) << testing::PrintToString(Refusals());
}

INSTANTIATE_TEST_SUITE_P(Descs, BadVolumeDesc, testing::ValuesIn(BadVolumes()),
                         [](const testing::TestParamInfo<BadVolume>& info) { return info.param.name; });

TEST_F(Texture3DTest, InitialDataWithPaddedRowAndDepthPitchesReadsBackThroughAStagingMap) {
  const TEXTURE3D_DESC desc = VolumeDesc(4, 2, 4, 3, BIND_SHADER_RESOURCE);
  ComPtr<Texture3D> texture = FilledVolume(desc);
  ASSERT_TRUE(texture);
  EXPECT_EQ(ReadVolume(texture.Get()), ExpectedVolume(desc));
}

TEST_F(Texture3DTest, UpdateSubresourceAndCopySubresourceRegionAddressWSlices) {
  const TEXTURE3D_DESC desc = VolumeDesc(4, 4, 4, 1, BIND_SHADER_RESOURCE);
  ComPtr<Texture3D> source = FilledVolume(desc), target;
  ASSERT_EQ(device->CreateTexture3D(&desc, nullptr, target.GetAddressOf()), S_OK);
  // Zero all of `target`, then write one white texel block x 1..2, y 0..1, W slices 2..3.
  const std::vector<uint32_t> zeros(64, 0), white(2 * 2 * 2, kWhitePx);
  context->UpdateSubresource(target.Get(), 0, nullptr, zeros.data(), 16, 64);
  const BOX box{1, 0, 2, 3, 2, 4};
  context->UpdateSubresource(target.Get(), 0, &box, white.data(), 8, 16);
  // Copy source's texels x 0..1, y 2..3, W slice 1 to (2, 2, 0) of target.
  const BOX from{0, 2, 1, 2, 4, 2};
  context->CopySubresourceRegion(target.Get(), 0, 2, 2, 0, source.Get(), 0, &from);
  std::vector<uint32_t> expected(64, 0);
  for (UINT z = 2; z < 4; ++z)
    for (UINT y = 0; y < 2; ++y)
      for (UINT x = 1; x < 3; ++x) expected[z * 16 + y * 4 + x] = kWhitePx;
  for (UINT y = 2; y < 4; ++y)
    for (UINT x = 2; x < 4; ++x) expected[y * 4 + x] = TexelValue(0, x - 2, y, 1);
  EXPECT_EQ(ReadVolume(target.Get()), expected);
  EXPECT_TRUE(Refusals().empty());
}

// A deferred context copies the bytes UpdateSubresource reads when it records the call:
// every W slice of the box, through its depth pitch.
TEST_F(Texture3DTest, DeferredUpdateSubresourceKeepsEveryWSliceOfTheBox) {
  ComPtr<Texture3D> target;
  ASSERT_EQ(device->CreateTexture3D(&kValidVolume, nullptr, target.GetAddressOf()), S_OK);
  ComPtr<DeviceContext> deferred;
  ASSERT_EQ(device->CreateDeferredContext(0, deferred.GetAddressOf()), S_OK);
  std::vector<uint32_t> all(64);
  for (UINT i = 0; i < 64; ++i) all[i] = TexelValue(0, i % 4, i / 4 % 4, i / 16);
  deferred->UpdateSubresource(target.Get(), 0, nullptr, all.data(), 16, 64);
  // Then W slices 1..2 of texels x 0..1, y 3 from a source with padded slices (depth pitch 32).
  std::vector<uint32_t> box(16, kWhitePx);
  const BOX region{0, 3, 1, 2, 4, 3};
  deferred->UpdateSubresource(target.Get(), 0, &region, box.data(), 8, 32);
  std::fill(box.begin(), box.end(), 0u);  // recorded: later changes to the source do not matter
  ComPtr<CommandList> list;
  ASSERT_EQ(deferred->FinishCommandList(FALSE, list.GetAddressOf()), S_OK);
  context->ExecuteCommandList(list.Get(), FALSE);
  std::vector<uint32_t> expected = all;
  for (UINT z = 1; z < 3; ++z)
    for (UINT x = 0; x < 2; ++x) expected[z * 16 + 12 + x] = kWhitePx;
  EXPECT_EQ(ReadVolume(target.Get()), expected);
  EXPECT_TRUE(Refusals().empty());
}

// A staging volume written through Map (its DepthPitch) reaches another staging volume and
// a default one through CopySubresourceRegion boxes with W offsets.
TEST_F(Texture3DTest, MappedStagingVolumeCopiesWSliceBoxesToStagingAndDefaultVolumes) {
  TEXTURE3D_DESC desc = VolumeDesc(2, 2, 3, 1, 0);
  desc.Usage = USAGE_STAGING;
  desc.CPUAccessFlags = CPU_ACCESS_READ | CPU_ACCESS_WRITE;
  ComPtr<Texture3D> source, middle, target;
  ASSERT_EQ(device->CreateTexture3D(&desc, nullptr, source.GetAddressOf()), S_OK);
  ASSERT_EQ(device->CreateTexture3D(&desc, nullptr, middle.GetAddressOf()), S_OK);
  MAPPED_SUBRESOURCE mapped{};
  ASSERT_EQ(context->Map(source.Get(), 0, MAP_WRITE, 0, &mapped), S_OK);
  ASSERT_EQ(mapped.DepthPitch, 16u);
  for (UINT z = 0; z < 3; ++z)
    for (UINT y = 0; y < 2; ++y)
      for (UINT x = 0; x < 2; ++x) {
        const uint32_t texel = TexelValue(0, x, y, z);
        std::memcpy(static_cast<uint8_t*>(mapped.pData) + z * mapped.DepthPitch + y * mapped.RowPitch + x * 4, &texel, 4);
      }
  context->Unmap(source.Get(), 0);
  // W slices 1..2 of source to W slices 0..1 of middle, then all of middle to W slice 1.. of target.
  const BOX upper{0, 0, 1, 2, 2, 3};
  context->CopySubresourceRegion(middle.Get(), 0, 0, 0, 0, source.Get(), 0, &upper);
  ASSERT_EQ(device->CreateTexture3D(&kValidVolume, nullptr, target.GetAddressOf()), S_OK);
  const std::vector<uint32_t> zeros(64, 0);
  context->UpdateSubresource(target.Get(), 0, nullptr, zeros.data(), 16, 64);
  const BOX firstTwo{0, 0, 0, 2, 2, 2};
  context->CopySubresourceRegion(target.Get(), 0, 1, 1, 1, middle.Get(), 0, &firstTwo);
  std::vector<uint32_t> expected(64, 0);
  for (UINT z = 0; z < 2; ++z)
    for (UINT y = 0; y < 2; ++y)
      for (UINT x = 0; x < 2; ++x) expected[(z + 1) * 16 + (y + 1) * 4 + x + 1] = TexelValue(0, x, y, z + 1);
  EXPECT_EQ(ReadVolume(target.Get()), expected);
  EXPECT_TRUE(Refusals().empty());
}

TEST_F(Texture3DTest, Texture3DViewSamplesEachWSlice) {
  // 2x1x4: slice z holds its own colour; the shader samples the centre of slice x of a 4x1 target.
  const TEXTURE3D_DESC desc = VolumeDesc(2, 1, 4, 1, BIND_SHADER_RESOURCE);
  const uint32_t colors[4] = {kRedPx, kGreenPx, kBluePx, kWhitePx};
  std::vector<uint32_t> texels;
  for (uint32_t color : colors) texels.insert(texels.end(), {color, color});
  const SUBRESOURCE_DATA data{texels.data(), 8, 8};
  ComPtr<Texture3D> texture;
  ASSERT_EQ(device->CreateTexture3D(&desc, &data, texture.GetAddressOf()), S_OK);
  ComPtr<ShaderResourceView> srv;
  ASSERT_EQ(device->CreateShaderResourceView(texture.Get(), nullptr, srv.GetAddressOf()), S_OK);
  Target target = MakeRenderTarget(4, 1);
  BindTarget(target.rtv.Get(), 4, 1);
  ComPtr<SamplerState> sampler = PointSampler();
  context->PSSetSamplers(0, 1, sampler.GetAddressOf());
  context->PSSetShaderResources(0, 1, srv.GetAddressOf());
  auto ps = PS(R"(Texture3D<float4> volume : register(t0);
    SamplerState point_ : register(s0);
    float4 main(float4 pos : SV_Position) : SV_Target {
      return volume.SampleLevel(point_, float3(0.25, 0.5, pos.x / 4), 0); })");
  DrawFullScreen(ps.Get());
  const std::vector<uint8_t> pixels = ReadTexture(target.texture.Get());
  for (UINT x = 0; x < 4; ++x) EXPECT_EQ(Pixel(pixels, 4, x, 0), colors[x]) << "W slice " << x;
}

// A TEXTURE3D view of levels 1.. of a 4x4x4 volume samples level 1 at its LOD 0; view
// dimensions must match the resource's (D3D11 refuses a 2D view of a volume and the reverse).
TEST_F(Texture3DTest, ViewFromTheMostDetailedMipSamplesThatLevelAndDimensionsMustMatch) {
  const TEXTURE3D_DESC desc = VolumeDesc(4, 4, 4, 2, BIND_SHADER_RESOURCE);
  ComPtr<Texture3D> texture = FilledVolume(desc);
  ASSERT_TRUE(texture);
  SHADER_RESOURCE_VIEW_DESC view{};
  view.Format = desc.Format;
  view.ViewDimension = SRV_DIMENSION_TEXTURE3D;
  view.Texture3D = {1, UINT(-1)};
  ComPtr<ShaderResourceView> srv;
  ASSERT_EQ(device->CreateShaderResourceView(texture.Get(), &view, srv.GetAddressOf()), S_OK);
  Target target = MakeRenderTarget(1, 1);
  BindTarget(target.rtv.Get(), 1, 1);
  context->PSSetShaderResources(0, 1, srv.GetAddressOf());
  // Texel (1, 0, 1) of level 1 (2x2x2): Load's mip index counts from the view's first level.
  auto ps = PS(R"(Texture3D<float4> volume : register(t0);
    float4 main(float4 pos : SV_Position) : SV_Target { return volume.Load(int4(1, 0, 1, 0)); })");
  DrawFullScreen(ps.Get());
  EXPECT_EQ(Pixel(ReadTexture(target.texture.Get()), 1, 0, 0), TexelValue(1, 1, 0, 1));
  view.Texture3D = {2, 1};
  EXPECT_EQ(device->CreateShaderResourceView(texture.Get(), &view, srv.ReleaseAndGetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("mip or array range outside the texture"));
  view.ViewDimension = SRV_DIMENSION_TEXTURE2D;
  view.Texture2D = {0, 1};
  EXPECT_EQ(device->CreateShaderResourceView(texture.Get(), &view, srv.ReleaseAndGetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("a 3D texture needs a *_TEXTURE3D ViewDimension"));
  ComPtr<Texture2D> flat = MakeTexture(4, 4, DXGI_FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE);
  view.ViewDimension = SRV_DIMENSION_TEXTURE3D;
  view.Texture3D = {0, 1};
  EXPECT_EQ(device->CreateShaderResourceView(flat.Get(), &view, srv.ReleaseAndGetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("a *_TEXTURE3D ViewDimension needs a 3D texture"));
}

TEST_F(Texture3DTest, RenderTargetViewsOfWSlicesClearAndDrawOnlyThoseSlices) {
  const TEXTURE3D_DESC desc = VolumeDesc(2, 2, 4, 1, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE);
  ComPtr<Texture3D> texture;
  ASSERT_EQ(device->CreateTexture3D(&desc, nullptr, texture.GetAddressOf()), S_OK);
  auto sliceView = [&](UINT first, UINT size) {
    RENDER_TARGET_VIEW_DESC view{};
    view.Format = desc.Format;
    view.ViewDimension = RTV_DIMENSION_TEXTURE3D;
    view.Texture3D = {0, first, size};
    ComPtr<RenderTargetView> rtv;
    EXPECT_EQ(device->CreateRenderTargetView(texture.Get(), &view, rtv.GetAddressOf()), S_OK);
    return rtv;
  };
  ComPtr<RenderTargetView> all = sliceView(0, UINT(-1)), middle = sliceView(1, 2), last = sliceView(3, 1);
  Clear(all.Get(), kBlue);
  Clear(middle.Get(), kRed);
  // A draw renders into the view's first W slice (no SV_RenderTargetArrayIndex).
  BindTarget(last.Get(), 2, 2);
  UseColorPipeline();
  DrawVertices(Quad(0, 0, 2, 2, kGreen, 2, 2));
  const uint32_t sliceColor[4] = {kBluePx, kRedPx, kRedPx, kGreenPx};
  const std::vector<uint32_t> texels = ReadVolume(texture.Get());
  ASSERT_EQ(texels.size(), 16u);
  for (UINT i = 0; i < 16; ++i) EXPECT_EQ(texels[i], sliceColor[i / 4]) << "texel " << i % 4 << " of W slice " << i / 4;
  // D3D11's W range: FirstWSlice + WSize within the mip's depth; a 2D view dimension does not view a volume.
  RENDER_TARGET_VIEW_DESC view{};
  view.Format = desc.Format;
  view.ViewDimension = RTV_DIMENSION_TEXTURE3D;
  view.Texture3D = {0, 3, 2};
  ComPtr<RenderTargetView> rtv;
  EXPECT_EQ(device->CreateRenderTargetView(texture.Get(), &view, rtv.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("slices 3+2 of 4"));
  view.ViewDimension = RTV_DIMENSION_TEXTURE2D;
  EXPECT_EQ(device->CreateRenderTargetView(texture.Get(), &view, rtv.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("a 3D texture needs a *_TEXTURE3D ViewDimension"));
}

TEST_F(Texture3DTest, ComputeShaderWritesEveryTexelOfARWTexture3D) {
  const TEXTURE3D_DESC desc = VolumeDesc(4, 2, 3, 1, BIND_UNORDERED_ACCESS, DXGI_FORMAT_R32_UINT);
  ComPtr<Texture3D> texture;
  ASSERT_EQ(device->CreateTexture3D(&desc, nullptr, texture.GetAddressOf()), S_OK);
  UNORDERED_ACCESS_VIEW_DESC view{};
  view.Format = DXGI_FORMAT_R32_UINT;
  view.ViewDimension = UAV_DIMENSION_TEXTURE3D;
  view.Texture3D = {0, 0, UINT(-1)};
  ComPtr<UnorderedAccessView> uav;
  ASSERT_EQ(device->CreateUnorderedAccessView(texture.Get(), &view, uav.GetAddressOf()), S_OK);
  auto cs = CS(R"(RWTexture3D<uint> volume : register(u0);
    [numthreads(4, 2, 1)] void main(uint3 id : SV_DispatchThreadID) { volume[id] = id.x + 10 * id.y + 100 * id.z; })");
  context->CSSetShader(cs.Get(), nullptr, 0);
  context->CSSetUnorderedAccessViews(0, 1, uav.GetAddressOf(), nullptr);
  context->Dispatch(1, 1, 3);
  // R32_UINT texels read as 4-byte values, in the same order as RGBA8 ones.
  const std::vector<uint32_t> texels = ReadVolume(texture.Get());
  ASSERT_EQ(texels.size(), 24u);
  for (UINT z = 0; z < 3; ++z)
    for (UINT y = 0; y < 2; ++y)
      for (UINT x = 0; x < 4; ++x) EXPECT_EQ(texels[z * 8 + y * 4 + x], x + 10 * y + 100 * z);
  // A view of some W slices has no Vulkan storage view: refused with the reason.
  view.Texture3D = {0, 1, 2};
  ComPtr<UnorderedAccessView> partial;
  EXPECT_EQ(device->CreateUnorderedAccessView(texture.Get(), &view, partial.GetAddressOf()), E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("cover every W slice of their mip"));
}

TEST_F(Texture3DTest, GenerateMipsAveragesEachTwoByTwoByTwoBlock) {
  TEXTURE3D_DESC desc = VolumeDesc(2, 2, 2, 2, BIND_SHADER_RESOURCE | BIND_RENDER_TARGET);
  desc.MiscFlags = RESOURCE_MISC_GENERATE_MIPS;
  ComPtr<Texture3D> texture;
  ASSERT_EQ(device->CreateTexture3D(&desc, nullptr, texture.GetAddressOf()), S_OK);
  // Red 8, 16, .., 64: multiples of 8, so every partial average (in any axis order, rounded
  // after each lerp or not) is exact; the mean is (8 + 64) / 2 = 36.
  std::vector<uint32_t> level0;
  for (UINT i = 0; i < 8; ++i) level0.push_back(RGBA(8 * (i + 1), 0, 0, 255));
  context->UpdateSubresource(texture.Get(), 0, nullptr, level0.data(), 8, 16);
  ComPtr<ShaderResourceView> srv;
  ASSERT_EQ(device->CreateShaderResourceView(texture.Get(), nullptr, srv.GetAddressOf()), S_OK);
  context->GenerateMips(srv.Get());
  const std::vector<uint32_t> texels = ReadVolume(texture.Get());
  ASSERT_EQ(texels.size(), 9u);
  EXPECT_EQ(texels[8], RGBA(36, 0, 0, 255));
}

}  // namespace
}  // namespace rhi_test
