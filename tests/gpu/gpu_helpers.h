// Helpers shared by the RHI GPU tests: a coloured-vertex pipeline, pixel-grid
// quads in D3D11 coordinates (x right, y down, pixel centres at .5) and
// coverage maps that make expected pixels readable in the test source.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gpu_test.h"

namespace rhi_test {

// An RGBA8 pixel as ReadTexture returns it (little-endian: R is the low byte).
constexpr uint32_t RGBA(uint32_t r, uint32_t g, uint32_t b, uint32_t a) { return r | g << 8 | b << 16 | a << 24; }

struct Color {
  float r, g, b, a;
};

// Exact colours (0 and 1 convert to 0 and 255 in any UNORM format) and their RGBA8 pixels.
inline constexpr Color kBlack{0, 0, 0, 1}, kRed{1, 0, 0, 1}, kGreen{0, 1, 0, 1}, kBlue{0, 0, 1, 1}, kWhite{1, 1, 1, 1};
inline constexpr uint32_t kBlackPx = RGBA(0, 0, 0, 255), kRedPx = RGBA(255, 0, 0, 255),
                          kGreenPx = RGBA(0, 255, 0, 255), kBluePx = RGBA(0, 0, 255, 255),
                          kWhitePx = RGBA(255, 255, 255, 255);
// The legend black '.', red 'R', green 'G', blue 'B', white 'W' for Picture.
inline const std::vector<std::pair<uint32_t, char>> kLegend = {
    {kBlackPx, '.'}, {kRedPx, 'R'}, {kGreenPx, 'G'}, {kBluePx, 'B'}, {kWhitePx, 'W'}};

// The vertex of the colour pipeline: clip-space position (w = 1) and a flat colour.
struct Vertex {
  float x, y, z;
  Color color;
};

// Six vertices (two triangles) covering exactly the pixels [x0,x1) x [y0,y1) of
// a width x height target whose viewport is the whole target. With
// clockwise = true both triangles are clockwise on screen (front-facing under
// the D3D11 default FrontCounterClockwise = FALSE).
std::vector<Vertex> Quad(float x0, float y0, float x1, float y1, Color color, UINT width, UINT height,
                         float z = 0.5f, bool clockwise = true);

// One character per pixel: 'X' where the pixel equals `lit`, '.' where it equals
// `background`, '?' anywhere else.
std::vector<std::string> CoverageMap(const std::vector<uint8_t>& rgba8, UINT width, UINT height, uint32_t lit,
                                     uint32_t background);
// One character per pixel from `legend` (pixel value -> character), '?' for
// values not in it.
std::vector<std::string> Picture(const std::vector<uint8_t>& rgba8, UINT width, UINT height,
                                 const std::vector<std::pair<uint32_t, char>>& legend);
// The four corners TL, TR, BL, BR of the pixel rectangle [x0,x1) x [y0,y1), for
// index buffers: {0,1,2, 2,1,3} draws it as two clockwise triangles.
std::vector<Vertex> Corners(float x0, float y0, float x1, float y1, Color color, UINT width, UINT height,
                            float z = 0.5f);
// `height` copies of `row`.
std::vector<std::string> Rows(UINT height, std::string_view row);
// Counts the pixels equal to `value`.
int CountPixels(const std::vector<uint8_t>& rgba8, uint32_t value);

class RhiGpuTest : public GpuTest {
 protected:
  // The colour pipeline: POSITION (float3) + COLOR (float4, flat) -> SV_Target.
  static constexpr const char* kColorVS = R"(
    struct VSIn { float3 pos : POSITION; nointerpolation float4 color : COLOR; };
    struct VSOut { float4 pos : SV_Position; nointerpolation float4 color : COLOR; };
    VSOut main(VSIn i) { VSOut o; o.pos = float4(i.pos, 1); o.color = i.color; return o; })";
  static constexpr const char* kColorPS = R"(
    float4 main(float4 pos : SV_Position, nointerpolation float4 color : COLOR) : SV_Target { return color; })";

  // Binds the colour pipeline (shaders, input layout, triangle list).
  void UseColorPipeline();
  // Binds `rtv` (and `dsv`) with a full width x height viewport.
  void BindTarget(rhi::RenderTargetView* rtv, UINT width, UINT height, rhi::DepthStencilView* dsv = nullptr);
  // Uploads `vertices` to an immutable vertex buffer, binds it to slot 0 and draws them.
  void DrawVertices(const std::vector<Vertex>& vertices);
  ComPtr<rhi::Buffer> VertexBuffer(const std::vector<Vertex>& vertices);
  void Clear(rhi::RenderTargetView* rtv, Color color);

  // A vertex shader together with an input layout matched against it.
  ComPtr<rhi::VertexShader> VSWithLayout(std::string_view source, const rhi::INPUT_ELEMENT_DESC* elements,
                                         UINT count, ComPtr<rhi::InputLayout>* layout);

  // A depth-stencil texture and its view.
  struct DepthTarget {
    ComPtr<rhi::Texture2D> texture;
    ComPtr<rhi::DepthStencilView> dsv;
  };
  DepthTarget MakeDepthTarget(UINT width, UINT height, rhi::DXGI_FORMAT format, UINT samples = 1);

  // A width x height texture of `format` with `bindFlags` and `samples` samples.
  ComPtr<rhi::Texture2D> MakeTexture(UINT width, UINT height, rhi::DXGI_FORMAT format, UINT bindFlags,
                                     UINT samples = 1);
  // Every sample of the width x height multisampled texture `srv` views, read
  // with Texture2DMS<`type`>.Load in a pixel shader and widened to float4:
  // element ((y * width + x) * samples + s) * 4 + c. Leaves the context cleared (ClearState).
  std::vector<float> ReadSamples(rhi::ShaderResourceView* srv, UINT width, UINT height, UINT samples,
                                 const char* type = "float4");
  // The texels of an R32_FLOAT, R32G32_FLOAT or R32G32B32A32_FLOAT texture (resolved if multisampled).
  std::vector<float> ReadFloats(rhi::Texture2D* texture);
  // Draws a triangle covering the whole viewport with `ps` and no input layout.
  void DrawFullScreen(rhi::PixelShader* ps);

  ComPtr<rhi::BlendState> Blend(const rhi::BLEND_DESC& desc);
  ComPtr<rhi::DepthStencilState> DepthStencil(const rhi::DEPTH_STENCIL_DESC& desc);
  ComPtr<rhi::RasterizerState> Rasterizer(const rhi::RASTERIZER_DESC& desc);
  ComPtr<rhi::SamplerState> PointSampler();

  ComPtr<rhi::VertexShader> fullScreenVS_;
  ComPtr<rhi::VertexShader> colorVS_;
  ComPtr<rhi::PixelShader> colorPS_;
  ComPtr<rhi::InputLayout> colorLayout_;
};

}  // namespace rhi_test
