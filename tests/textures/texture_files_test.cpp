// rhi/texture_files.h: DDS files written byte by byte here (dds_writer.h) and PNGs written
// with stb_image_write, loaded, sampled or read back on the device (validation on).
#include "rhi/texture_files.h"

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "dds_writer.h"
#include "gpu_test.h"
#include "rhi/capture.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

namespace textures_test {
namespace {

namespace fs = std::filesystem;
using rhi::ComPtr;
using rhi::UINT;

// BC1 in 4-colour mode, c0 = pure red (0xF800), c1 = pure blue (0x001F); row y uses index y.
// Decoded by the BC1 rule (D3D11 functional spec 19.5.2: c2 = (2 c0 + c1) / 3,
// c3 = (c0 + 2 c1) / 3, 5-bit 31 -> 255): row 0 red, row 1 blue, row 2 (170, 0, 85),
// row 3 (85, 0, 170), alpha 255 everywhere.
const std::vector<uint8_t> kRowsBlock = Bc1Block(0xF800, 0x001F, 0x00 | 0x55 << 8 | 0xAA << 16 | 0xFFu << 24);
const uint8_t kRowColors[4][3] = {{255, 0, 0}, {0, 0, 255}, {170, 0, 85}, {85, 0, 170}};

class TextureFilesTest : public rhi_test::GpuTest {
 protected:
  void SetUp() override {
    GpuTest::SetUp();
    folder = fs::temp_directory_path() / ("texture_files_" + std::to_string(::getpid()));
    fs::create_directories(folder);
  }
  void TearDown() override {
    fs::remove_all(folder);
    GpuTest::TearDown();
  }

  fs::path WriteFile(const std::string& name, const std::vector<uint8_t>& bytes) {
    std::ofstream(folder / name, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    return folder / name;
  }

  // Draws `pixelShader` (reading t0 through sampler s0, point filtering) over a width x height
  // RGBA8 target and returns its pixels.
  std::vector<uint8_t> Draw(rhi::ShaderResourceView* srv, const char* pixelShader, UINT width, UINT height) {
    Target target = MakeRenderTarget(width, height);
    auto vs = VS(R"(float4 main(uint id : SV_VertexID) : SV_Position {
      float2 uv = float2((id << 1) & 2, id & 2); return float4(uv * float2(2, -2) + float2(-1, 1), 0, 1); })");
    auto ps = PS(pixelShader);
    rhi::SAMPLER_DESC samplerDesc{};
    samplerDesc.Filter = rhi::FILTER_MIN_MAG_MIP_POINT;
    samplerDesc.AddressU = samplerDesc.AddressV = samplerDesc.AddressW = rhi::TEXTURE_ADDRESS_CLAMP;
    samplerDesc.MaxLOD = 1000;
    ComPtr<rhi::SamplerState> sampler;
    EXPECT_EQ(device->CreateSamplerState(&samplerDesc, sampler.GetAddressOf()), rhi::S_OK);
    context->OMSetRenderTargets(1, target.rtv.GetAddressOf(), nullptr);
    SetViewport(width, height);
    context->IASetPrimitiveTopology(rhi::PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    context->VSSetShader(vs.Get(), nullptr, 0);
    context->PSSetShader(ps.Get(), nullptr, 0);
    context->PSSetShaderResources(0, 1, &srv);
    context->PSSetSamplers(0, 1, sampler.GetAddressOf());
    context->Draw(3, 0);
    return ReadTexture(target.texture.Get());
  }

  fs::path folder;
  std::string error;
};

void ExpectNear(const std::vector<uint8_t>& pixels, size_t index, const uint8_t (&rgb)[3], const std::string& where) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(pixels[index * 4 + c], rgb[c], 1) << where << " channel " << c;
  EXPECT_EQ(pixels[index * 4 + 3], 255) << where;
}

TEST_F(TextureFilesTest, Bc1BlockSamplesToItsDecodedColours) {
  const std::vector<uint8_t> file = WriteDds({}, kRowsBlock);  // legacy header, FourCC DXT1
  ComPtr<rhi::Resource> texture;
  ComPtr<rhi::ShaderResourceView> srv;
  ASSERT_EQ(rhi::CreateDDSTextureFromMemory(device.Get(), file.data(), file.size(), texture.GetAddressOf(),
                                            srv.GetAddressOf(), 0, nullptr, &error),
            rhi::S_OK)
      << error;
  const auto pixels = Draw(srv.Get(), "Texture2D t : register(t0); "
                                      "float4 main(float4 p : SV_Position) : SV_Target { return t.Load(int3(p.xy, 0)); }",
                           4, 4);
  for (UINT y = 0; y < 4; ++y)
    for (UINT x = 0; x < 4; ++x) ExpectNear(pixels, y * 4 + x, kRowColors[y], "texel " + std::to_string(x) + "," + std::to_string(y));
  EXPECT_TRUE(Refusals().empty());
}

// DX10 header, BC1_UNORM, an array of 2 slices of 8x8 with 4 mip levels (blocks: 2x2, 1, 1, 1):
// every subresource reads back (CaptureTexture2D: a block-compressed staging copy) as written.
TEST_F(TextureFilesTest, Bc1ArrayMipChainReadsBackBlockForBlock) {
  DdsShape shape{.width = 8, .height = 8, .mips = 4, .format = kDx10, .dxgiFormat = rhi::DXGI_FORMAT_BC1_UNORM,
                 .arraySize = 2};
  std::vector<uint8_t> texels;
  for (int i = 0; i < 2 * (4 + 1 + 1 + 1); ++i) {
    auto block = Bc1Block(uint16_t(0xF800 | i), 0x001F, 0x1B1B1B1Bu * uint32_t(i % 3));
    texels.insert(texels.end(), block.begin(), block.end());
  }
  const std::vector<uint8_t> file = WriteDds(shape, texels);
  rhi::DDS_TEXTURE parsed;
  ASSERT_EQ(rhi::ParseDDS(file.data(), file.size(), "array.dds", &parsed, &error), rhi::S_OK) << error;
  ASSERT_EQ(parsed.Subresources.size(), 8u);
  EXPECT_EQ(parsed.Subresources[0].SysMemPitch, 16u);  // two 8-byte blocks a row
  EXPECT_EQ(parsed.Subresources[0].SysMemSlicePitch, 32u);
  EXPECT_EQ(parsed.Subresources[3].SysMemPitch, 8u);  // 1x1: one block

  ComPtr<rhi::Resource> resource;
  ASSERT_EQ(rhi::CreateDDSTextureFromMemory(device.Get(), file.data(), file.size(), resource.GetAddressOf(), nullptr,
                                            0, nullptr, &error),
            rhi::S_OK)
      << error;
  ComPtr<rhi::Texture2D> texture;
  texture.Attach(static_cast<rhi::Texture2D*>(resource.Detach()));
  rhi::TEXTURE2D_DESC desc;
  texture->GetDesc(&desc);
  EXPECT_EQ(desc.Format, rhi::DXGI_FORMAT_BC1_UNORM);
  EXPECT_EQ(desc.MipLevels, 4u);
  EXPECT_EQ(desc.ArraySize, 2u);
  for (UINT sub = 0; sub < 8; ++sub) {
    std::vector<uint8_t> read;
    ASSERT_EQ(rhi::CaptureTexture2D(device.Get(), context.Get(), texture.Get(), sub, &read), rhi::S_OK);
    const auto* begin = static_cast<const uint8_t*>(parsed.Subresources[sub].pSysMem);
    EXPECT_EQ(read, std::vector<uint8_t>(begin, begin + parsed.Subresources[sub].SysMemSlicePitch)) << "subresource " << sub;
  }
  EXPECT_TRUE(Refusals().empty());
}

// D3D11's rules for block-compressed textures in the RHI: shader resources only, and
// updates and copies on whole 4x4 blocks (ending at the subresource's edge is allowed).
TEST_F(TextureFilesTest, BlockCompressedTexturesFollowD3D11Rules) {
  rhi::TEXTURE2D_DESC desc{8, 8, 1, 1, rhi::DXGI_FORMAT_BC3_UNORM, {1, 0}, rhi::USAGE_DEFAULT,
                           rhi::BIND_SHADER_RESOURCE | rhi::BIND_RENDER_TARGET, 0, 0};
  ComPtr<rhi::Texture2D> texture;
  EXPECT_EQ(device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()), rhi::E_INVALIDARG);
  EXPECT_TRUE(RefusedWith("DXGI_FORMAT_BC3_UNORM textures can only have BIND_SHADER_RESOURCE")) << Refusals()[0];
  ClearMessages();
  desc.BindFlags = rhi::BIND_SHADER_RESOURCE;
  desc.Width = desc.Height = 6;  // not a multiple of 4: D3D11.0 allows it, the last blocks are partly used
  ASSERT_EQ(device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()), rhi::S_OK);
  const std::vector<uint8_t> blocks(4 * 16, 0x5A);
  const rhi::BOX misaligned{2, 0, 0, 6, 4, 1};
  context->UpdateSubresource(texture.Get(), 0, &misaligned, blocks.data(), 16, 0);
  EXPECT_TRUE(RefusedWith("is not aligned to its 4x4 blocks")) << (Refusals().empty() ? "" : Refusals()[0]);
  ClearMessages();
  const rhi::BOX toTheEdge{4, 4, 0, 6, 6, 1};  // a partial block at the corner
  context->UpdateSubresource(texture.Get(), 0, &toTheEdge, blocks.data(), 16, 0);
  std::vector<uint8_t> read;
  ASSERT_EQ(rhi::CaptureTexture2D(device.Get(), context.Get(), texture.Get(), 0, &read), rhi::S_OK);
  ASSERT_EQ(read.size(), 4u * 16);  // 2x2 blocks
  EXPECT_EQ(std::vector<uint8_t>(read.begin() + 48, read.end()), std::vector<uint8_t>(16, 0x5A));
  EXPECT_TRUE(Refusals().empty());
}

// A legacy RGBA8 cube map, one colour per face, sampled along each axis.
TEST_F(TextureFilesTest, CubeMapFacesAreSampledAlongTheirAxes) {
  const uint8_t faces[6][3] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 0}, {0, 255, 255}, {255, 0, 255}};
  std::vector<uint8_t> texels;
  for (const auto& face : faces)
    for (int texel = 0; texel < 4; ++texel) texels.insert(texels.end(), {face[0], face[1], face[2], 255});
  const fs::path path =
      WriteFile("sky.dds", WriteDds({.width = 2, .height = 2, .format = kRgba8, .caps2 = 0xFE00}, texels));
  ComPtr<rhi::ShaderResourceView> srv;
  ASSERT_EQ(rhi::CreateDDSTextureFromFile(device.Get(), path, nullptr, srv.GetAddressOf(), 0, nullptr, &error),
            rhi::S_OK)
      << error;
  const auto pixels = Draw(srv.Get(), R"(TextureCube t : register(t0); SamplerState s : register(s0);
    float4 main(float4 p : SV_Position) : SV_Target {
      static const float3 axes[6] = {float3(1,0,0), float3(-1,0,0), float3(0,1,0), float3(0,-1,0), float3(0,0,1), float3(0,0,-1)};
      return t.SampleLevel(s, axes[uint(p.x)], 0); })",
                           6, 1);
  for (UINT face = 0; face < 6; ++face) ExpectNear(pixels, face, faces[face], "face " + std::to_string(face));
  EXPECT_TRUE(Refusals().empty());
}

// A DX10 cube-map array (two cubes, one colour per cube and face) loads with a
// TEXTURECUBEARRAY view of both cubes; each cube is sampled along each axis. The colours
// are the written texels themselves (RGBA8, point sampling of a one-colour face).
TEST_F(TextureFilesTest, CubeMapArrayLoadsWithACubeArrayViewOfEveryCube) {
  constexpr UINT kCubes = 2;
  auto colour = [](UINT cube, UINT face) { return std::array<uint8_t, 3>{uint8_t(40 * face), uint8_t(255 * cube), 100}; };
  std::vector<uint8_t> texels;
  for (UINT cube = 0; cube < kCubes; ++cube)
    for (UINT face = 0; face < 6; ++face)
      for (int texel = 0; texel < 4; ++texel) {
        const auto c = colour(cube, face);
        texels.insert(texels.end(), {c[0], c[1], c[2], 255});
      }
  const auto file = WriteDds({.width = 2, .height = 2, .format = kDx10, .dxgiFormat = rhi::DXGI_FORMAT_R8G8B8A8_UNORM,
                              .miscFlag = 0x4 /* DDS_RESOURCE_MISC_TEXTURECUBE */, .arraySize = kCubes},
                             texels);
  ComPtr<rhi::ShaderResourceView> srv;
  ASSERT_EQ(rhi::CreateDDSTextureFromMemory(device.Get(), file.data(), file.size(), nullptr, srv.GetAddressOf(), 0,
                                            nullptr, &error),
            rhi::S_OK)
      << error;
  rhi::SHADER_RESOURCE_VIEW_DESC view;
  srv->GetDesc(&view);
  EXPECT_EQ(view.ViewDimension, rhi::SRV_DIMENSION_TEXTURECUBEARRAY);
  EXPECT_EQ(view.TextureCubeArray.NumCubes, kCubes);
  const auto pixels = Draw(srv.Get(), R"(TextureCubeArray t : register(t0); SamplerState s : register(s0);
    float4 main(float4 p : SV_Position) : SV_Target {
      static const float3 axes[6] = {float3(1,0,0), float3(-1,0,0), float3(0,1,0), float3(0,-1,0), float3(0,0,1), float3(0,0,-1)};
      return t.SampleLevel(s, float4(axes[uint(p.x)], uint(p.y)), 0); })",
                           6, kCubes);
  for (UINT cube = 0; cube < kCubes; ++cube)
    for (UINT face = 0; face < 6; ++face) {
      const auto c = colour(cube, face);
      const uint8_t rgb[3] = {c[0], c[1], c[2]};
      ExpectNear(pixels, cube * 6 + face, rgb, "cube " + std::to_string(cube) + " face " + std::to_string(face));
    }
  EXPECT_TRUE(Refusals().empty());
}

TEST_F(TextureFilesTest, OneDimensionalTextureFromTheDx10Header) {
  const std::vector<uint8_t> texels(4 * 4, 200);
  const auto file = WriteDds({.width = 4, .height = 1, .format = kDx10,
                              .dxgiFormat = rhi::DXGI_FORMAT_R8G8B8A8_UNORM, .dimension = 2},
                             texels);
  ComPtr<rhi::Resource> texture;
  ComPtr<rhi::ShaderResourceView> srv;
  ASSERT_EQ(rhi::CreateDDSTextureFromMemory(device.Get(), file.data(), file.size(), texture.GetAddressOf(),
                                            srv.GetAddressOf(), 0, nullptr, &error),
            rhi::S_OK)
      << error;
  rhi::RESOURCE_DIMENSION dimension;
  texture->GetType(&dimension);
  EXPECT_EQ(dimension, rhi::RESOURCE_DIMENSION_TEXTURE1D);
}

// A legacy-header volume (DDSCAPS2_VOLUME, RGBA8) of 2x2x4 with its full chain (2x2x4,
// 1x1x2, 1x1x1): a Texture3D with a TEXTURE3D view, every W slice of every level as written.
TEST_F(TextureFilesTest, VolumeWithAMipChainLoadsEveryWSliceOfEveryLevel) {
  constexpr UINT kDepths[3] = {4, 2, 1}, kTexels[3] = {4, 1, 1};
  auto color = [](UINT mip, UINT slice) { return std::array<uint8_t, 4>{uint8_t(10 + 80 * mip + 20 * slice),
                                                                         uint8_t(60 * slice), uint8_t(100 * mip), 255}; };
  std::vector<uint8_t> texels;
  for (UINT mip = 0; mip < 3; ++mip)
    for (UINT slice = 0; slice < kDepths[mip]; ++slice)
      for (UINT i = 0; i < kTexels[mip]; ++i) {
        const auto rgba = color(mip, slice);
        texels.insert(texels.end(), rgba.begin(), rgba.end());
      }
  const auto path = WriteFile("fog.dds", WriteDds({.width = 2, .height = 2, .depth = 4, .mips = 3, .format = kRgba8,
                                                   .caps2 = 0x200000},
                                                  texels));
  ComPtr<rhi::Resource> texture;
  ComPtr<rhi::ShaderResourceView> srv;
  ASSERT_EQ(rhi::CreateDDSTextureFromFile(device.Get(), path, texture.GetAddressOf(), srv.GetAddressOf(), 0, nullptr,
                                          &error),
            rhi::S_OK)
      << error;
  rhi::RESOURCE_DIMENSION dimension;
  texture->GetType(&dimension);
  ASSERT_EQ(dimension, rhi::RESOURCE_DIMENSION_TEXTURE3D);
  rhi::TEXTURE3D_DESC desc;
  static_cast<rhi::Texture3D*>(texture.Get())->GetDesc(&desc);
  EXPECT_EQ(desc.Depth, 4u);
  EXPECT_EQ(desc.MipLevels, 3u);
  rhi::SHADER_RESOURCE_VIEW_DESC view;
  srv->GetDesc(&view);
  EXPECT_EQ(view.ViewDimension, rhi::SRV_DIMENSION_TEXTURE3D);
  // Pixel (x, y): texel (0, 0) of W slice x of level y (black past the level's depth).
  const auto pixels = Draw(srv.Get(), R"(Texture3D t : register(t0);
    float4 main(float4 p : SV_Position) : SV_Target {
      uint w, h, d, levels;
      t.GetDimensions(uint(p.y), w, h, d, levels);
      return uint(p.x) < d ? t.Load(int4(0, 0, p.x, p.y)) : float4(0, 0, 0, 1); })",
                           4, 3);
  for (UINT mip = 0; mip < 3; ++mip)
    for (UINT slice = 0; slice < kDepths[mip]; ++slice) {
      const auto rgba = color(mip, slice);
      const uint8_t rgb[3] = {rgba[0], rgba[1], rgba[2]};
      ExpectNear(pixels, mip * 4 + slice, rgb, "level " + std::to_string(mip) + " W slice " + std::to_string(slice));
    }
  EXPECT_TRUE(Refusals().empty());
}

// The DX10 header's TEXTURE3D dimension with a block-compressed format: BC1, 4x4x2, one block a slice.
TEST_F(TextureFilesTest, Bc1VolumeFromTheDx10HeaderDecodesEachWSlice) {
  std::vector<uint8_t> texels = kRowsBlock;
  const auto green = Bc1Block(0x07E0, 0x0000, 0);  // every texel c0: pure green
  texels.insert(texels.end(), green.begin(), green.end());
  const auto file = WriteDds({.width = 4, .height = 4, .depth = 2, .format = kDx10,
                              .dxgiFormat = rhi::DXGI_FORMAT_BC1_UNORM, .dimension = 4},
                             texels);
  ComPtr<rhi::ShaderResourceView> srv;
  ASSERT_EQ(rhi::CreateDDSTextureFromMemory(device.Get(), file.data(), file.size(), nullptr, srv.GetAddressOf(), 0,
                                            nullptr, &error),
            rhi::S_OK)
      << error;
  // Rows 0..3: W slice 0; rows 4..7: W slice 1.
  const auto pixels = Draw(srv.Get(), R"(Texture3D t : register(t0);
    float4 main(float4 p : SV_Position) : SV_Target { return t.Load(int4(p.x, uint(p.y) % 4, uint(p.y) / 4, 0)); })",
                           4, 8);
  const uint8_t kGreen[3] = {0, 255, 0};
  for (UINT y = 0; y < 8; ++y)
    for (UINT x = 0; x < 4; ++x)
      ExpectNear(pixels, y * 4 + x, y < 4 ? kRowColors[y] : kGreen,
                 "texel " + std::to_string(x) + "," + std::to_string(y % 4) + " of W slice " + std::to_string(y / 4));
  EXPECT_TRUE(Refusals().empty());
}

// Every damaged file fails with "<name>: <problem>" and no device message.
struct BadFile {
  const char* name;
  std::vector<uint8_t> bytes;
  const char* problem;
};

std::vector<uint8_t> Patched(std::vector<uint8_t> file, size_t offset, uint32_t value) {
  std::memcpy(file.data() + offset, &value, 4);
  return file;
}

std::vector<BadFile> BadFiles() {
  const auto good = WriteDds({}, kRowsBlock);
  const auto dx10 = WriteDds({.format = kDx10, .dxgiFormat = rhi::DXGI_FORMAT_BC1_UNORM}, kRowsBlock);
  // Byte offsets: 4 header size, 12 height, 16 width, 28 mip count, 76 pixel-format size, 84 FourCC,
  // 112 caps2, 128 DX10 format, 132 dimension, 140 array size.
  return {
      {"empty", {}, "not a DDS file: 0 bytes"},
      {"png_magic", Patched(good, 0, 0x474E5089), "not a DDS file: the magic is '\\x137PNG', not 'DDS '"},
      {"short_header", std::vector<uint8_t>(good.begin(), good.begin() + 60), "truncated: 60 bytes, the header needs 128"},
      {"header_size", Patched(good, 4, 100), "the header size is 100, not 124"},
      {"pixel_format_size", Patched(good, 76, 16), "the pixel-format size is 16, not 32"},
      {"truncated_texels", std::vector<uint8_t>(good.begin(), good.end() - 1), "truncated: slice 0 mip 0 needs bytes 128..136 of a 135-byte file"},
      {"huge_width", Patched(good, 16, 0xFFFFFFFF), "size 4294967295x4 exceeds D3D11's limit of 16384"},
      {"zero_height", Patched(good, 12, 0), "an empty texture (4x0)"},
      {"too_many_mips", Patched(good, 28, 40), "40 mip levels, more than the full chain of 3 for 4x4"},
      {"unknown_fourcc", Patched(good, 84, FourCC("ABCD")), "the legacy FourCC 'ABCD' (1145258561) is not supported"},
      {"unknown_dxgi_format", Patched(dx10, 128, 1000), "DXGI_FORMAT 1000 is not supported"},
      {"undeclared_dxgi_format", Patched(dx10, 128, 85), "DXGI_FORMAT 85 is not supported"},
      {"bad_dimension", Patched(dx10, 132, 7), "the DX10 header's resource dimension 7 is not 2, 3 or 4"},
      {"zero_array", Patched(dx10, 140, 0), "the DX10 header's array size is 0"},
      {"huge_array", Patched(dx10, 140, 0x80000000), "array size 2147483648 exceeds D3D11's limit of 2048 slices"},
      {"short_dx10", std::vector<uint8_t>(dx10.begin(), dx10.begin() + 140), "truncated: 140 bytes, the DX10 header needs 148"},
      {"partial_cube", Patched(good, 112, 0x200 | 0x400), "a cube map with only some faces"},
      {"truncated_volume",
       WriteDds({.width = 2, .height = 2, .depth = 2, .mips = 2, .format = kRgba8, .caps2 = 0x200000},
                std::vector<uint8_t>(2 * 2 * 2 * 4 + 4 - 1)),
       "truncated: slice 0 mip 1 needs bytes 160..164 of a 163-byte file (2x2x2, 2 mip levels, 1 slices)"},
      {"volume_array", Patched(Patched(dx10, 132, 4), 140, 2), "a 3D texture with array size 2"},
      {"volume_too_deep",
       WriteDds({.width = 4, .height = 4, .depth = 4096, .format = kRgba8, .caps2 = 0x200000}, {}),
       "size 4x4x4096 exceeds D3D11's limit of 2048"},
  };
}

class BadDdsFile : public TextureFilesTest, public testing::WithParamInterface<BadFile> {};

TEST_P(BadDdsFile, IsRefusedNamingTheFileAndTheProblem) {
  const BadFile& bad = GetParam();
  const fs::path path = WriteFile(std::string(bad.name) + ".dds", bad.bytes);
  ComPtr<rhi::ShaderResourceView> srv;
  EXPECT_EQ(rhi::CreateDDSTextureFromFile(device.Get(), path, nullptr, srv.GetAddressOf(), 0, nullptr, &error),
            rhi::E_FAIL);
  EXPECT_EQ(srv.Get(), nullptr);
  EXPECT_EQ(error.rfind(path.string() + ": ", 0), 0u) << error;
  EXPECT_NE(error.find(bad.problem), std::string::npos) << error;
  EXPECT_TRUE(Refusals().empty());
}

INSTANTIATE_TEST_SUITE_P(Files, BadDdsFile, testing::ValuesIn(BadFiles()),
                         [](const testing::TestParamInfo<BadFile>& info) { return info.param.name; });

TEST_F(TextureFilesTest, MissingFileIsNamed) {
  ComPtr<rhi::ShaderResourceView> srv;
  EXPECT_EQ(rhi::CreateDDSTextureFromFile(device.Get(), folder / "nope.dds", nullptr, srv.GetAddressOf(), 0, nullptr,
                                          &error),
            rhi::E_FAIL);
  EXPECT_EQ(error, (folder / "nope.dds").string() + ": cannot open the file");
}

// D3D11 programs pass wide paths; non-ASCII names work whatever the C locale.
TEST_F(TextureFilesTest, WidePathsLoad) {
  WriteFile(reinterpret_cast<const char*>(u8"brique_\u00e9\u6587.dds"), WriteDds({}, kRowsBlock));
  const std::string ascii = folder.string();
  std::wstring wide(ascii.begin(), ascii.end());
  wide += L"/brique_\u00e9\u6587.dds";
  ComPtr<rhi::ShaderResourceView> srv;
  EXPECT_EQ(rhi::CreateDDSTextureFromFile(device.Get(), wide.c_str(), nullptr, srv.GetAddressOf(), 0, nullptr, &error),
            rhi::S_OK)
      << error;
}

// A 2x2 PNG: white, black / white, black. With a context the chain is 2x2, 1x1; the 1x1
// level is the mean: 127.5 -> 128 as UNORM, and in linear light 0.5 -> sRGB 188 as _SRGB
// (0.5^(1/2.4) * 1.055 - 0.055 = 0.7354, * 255 = 187.5 -> 188).
TEST_F(TextureFilesTest, PngLoadsWithMipsAndSrgbChoice) {
  const uint8_t pixels[16] = {255, 255, 255, 255, 0, 0, 0, 255, 255, 255, 255, 255, 0, 0, 0, 255};
  int length = 0;
  unsigned char* png = stbi_write_png_to_mem(pixels, 8, 2, 2, 4, &length);
  ASSERT_NE(png, nullptr);
  const fs::path path = WriteFile("checker.png", std::vector<uint8_t>(png, png + length));
  STBIW_FREE(png);
  for (auto [flags, format, mean] : {std::tuple{rhi::WIC_LOADER_DEFAULT, rhi::DXGI_FORMAT_R8G8B8A8_UNORM, 128},
                                     std::tuple{rhi::WIC_LOADER_FORCE_SRGB, rhi::DXGI_FORMAT_R8G8B8A8_UNORM_SRGB, 188}}) {
    ComPtr<rhi::Resource> resource;
    ASSERT_EQ(rhi::CreateWICTextureFromFileEx(device.Get(), context.Get(), path, 0, rhi::USAGE_DEFAULT,
                                              rhi::BIND_SHADER_RESOURCE, 0, 0, flags, resource.GetAddressOf(), nullptr,
                                              &error),
              rhi::S_OK)
        << error;
    ComPtr<rhi::Texture2D> texture;
    texture.Attach(static_cast<rhi::Texture2D*>(resource.Detach()));
    rhi::TEXTURE2D_DESC desc;
    texture->GetDesc(&desc);
    EXPECT_EQ(desc.Format, format);
    EXPECT_EQ(desc.MipLevels, 2u);
    std::vector<uint8_t> top, bottom;
    ASSERT_EQ(rhi::CaptureTexture2D(device.Get(), context.Get(), texture.Get(), 0, &top), rhi::S_OK);
    ASSERT_EQ(rhi::CaptureTexture2D(device.Get(), context.Get(), texture.Get(), 1, &bottom), rhi::S_OK);
    EXPECT_EQ(top, std::vector<uint8_t>(pixels, pixels + 16));
    EXPECT_EQ(bottom, (std::vector<uint8_t>{uint8_t(mean), uint8_t(mean), uint8_t(mean), 255}));
  }
  ComPtr<rhi::ShaderResourceView> oneLevel;  // no context: no mips
  ASSERT_EQ(rhi::CreateWICTextureFromFile(device.Get(), nullptr, path, nullptr, oneLevel.GetAddressOf(), 0, &error),
            rhi::S_OK);
  EXPECT_TRUE(Refusals().empty());
}

// A JPEG from stb_image_write loads (its Huffman tables pass the loader's DHT check), and
// one whose table declares 272 codes is refused before stb_image would overflow its table.
TEST_F(TextureFilesTest, JpegLoadsAndCorruptHuffmanTablesAreRefused) {
  std::vector<uint8_t> jpeg;
  const std::vector<uint8_t> grey(8 * 8 * 3, 128);
  ASSERT_NE(stbi_write_jpg_to_func(
                [](void* out, void* data, int size) {
                  auto* bytes = static_cast<uint8_t*>(data);
                  static_cast<std::vector<uint8_t>*>(out)->insert(static_cast<std::vector<uint8_t>*>(out)->end(),
                                                                  bytes, bytes + size);
                },
                &jpeg, 8, 8, 3, grey.data(), 90),
            0);
  ComPtr<rhi::Resource> texture;
  ASSERT_EQ(rhi::CreateWICTextureFromMemory(device.Get(), nullptr, jpeg.data(), jpeg.size(), texture.GetAddressOf(),
                                            nullptr, 0, &error),
            rhi::S_OK)
      << error;
  const std::vector<uint8_t> corrupt{0xFF, 0xD8, 0xFF, 0xC4, 0x00, 0x13, 0x00, 0x11, 0xFF, 0, 0, 0, 0, 0,
                                     0,    0,    0,    0,    0,    0,    0,    0,    0,    0,    0};
  EXPECT_EQ(rhi::CreateWICTextureFromMemory(device.Get(), nullptr, corrupt.data(), corrupt.size(),
                                            texture.ReleaseAndGetAddressOf(), nullptr, 0, &error),
            rhi::E_FAIL);
  EXPECT_EQ(error, "<memory>: corrupt JPEG: a Huffman table at byte 2 declares 272 codes (at most 256)");
}

// stb_image reads zeros past the end of a TGA; the loader checks the header's size instead
// (the fuzzer's finding: tests/fuzz/texture_corpus/regression_tga_truncated_17_bytes.tga).
TEST_F(TextureFilesTest, TruncatedTgaIsNamed) {
  std::vector<uint8_t> tga{0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 2, 0, 32, 8};  // 2x2, 32 bits
  tga.resize(tga.size() + 8);                                                      // half the pixels
  const fs::path path = WriteFile("half.tga", tga);
  ComPtr<rhi::ShaderResourceView> srv;
  EXPECT_EQ(rhi::CreateWICTextureFromFile(device.Get(), nullptr, path, nullptr, srv.GetAddressOf(), 0, &error),
            rhi::E_FAIL);
  EXPECT_EQ(error, path.string() + ": truncated: a 2x2 TGA needs 34 bytes, the file has 26");
}

TEST_F(TextureFilesTest, NotAnImageIsNamed) {
  const fs::path path = WriteFile("notes.png", {'h', 'e', 'l', 'l', 'o'});
  ComPtr<rhi::ShaderResourceView> srv;
  EXPECT_EQ(rhi::CreateWICTextureFromFile(device.Get(), nullptr, path, nullptr, srv.GetAddressOf(), 0, &error),
            rhi::E_FAIL);
  EXPECT_EQ(error.rfind(path.string() + ": not a PNG, JPEG, TGA or BMP image", 0), 0u) << error;
}

}  // namespace
}  // namespace textures_test
