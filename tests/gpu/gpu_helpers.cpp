#include "gpu_helpers.h"

#include <cstring>

namespace rhi_test {

using namespace rhi;

std::vector<Vertex> Quad(float x0, float y0, float x1, float y1, Color color, UINT width, UINT height, float z,
                         bool clockwise) {
  auto X = [&](float px) { return px / static_cast<float>(width) * 2.0f - 1.0f; };
  auto Y = [&](float py) { return 1.0f - py / static_cast<float>(height) * 2.0f; };
  const Vertex tl{X(x0), Y(y0), z, color}, tr{X(x1), Y(y0), z, color};
  const Vertex bl{X(x0), Y(y1), z, color}, br{X(x1), Y(y1), z, color};
  // On screen (y down) TL -> TR -> BL turns clockwise, TL -> BL -> TR counter-clockwise.
  if (clockwise) return {tl, tr, bl, bl, tr, br};
  return {tl, bl, tr, bl, br, tr};
}

std::vector<std::string> CoverageMap(const std::vector<uint8_t>& rgba8, UINT width, UINT height, uint32_t lit,
                                     uint32_t background) {
  std::vector<std::string> rows(height, std::string(width, '?'));
  for (UINT y = 0; y < height; ++y)
    for (UINT x = 0; x < width; ++x) {
      uint32_t p;
      std::memcpy(&p, rgba8.data() + (static_cast<size_t>(y) * width + x) * 4, 4);
      rows[y][x] = p == lit ? 'X' : p == background ? '.' : '?';
    }
  return rows;
}

std::vector<std::string> Picture(const std::vector<uint8_t>& rgba8, UINT width, UINT height,
                                 const std::vector<std::pair<uint32_t, char>>& legend) {
  std::vector<std::string> rows(height, std::string(width, '?'));
  for (UINT y = 0; y < height; ++y)
    for (UINT x = 0; x < width; ++x) {
      uint32_t p;
      std::memcpy(&p, rgba8.data() + (static_cast<size_t>(y) * width + x) * 4, 4);
      for (const auto& [value, c] : legend)
        if (p == value) rows[y][x] = c;
    }
  return rows;
}

std::vector<Vertex> Corners(float x0, float y0, float x1, float y1, Color color, UINT width, UINT height, float z) {
  std::vector<Vertex> quad = Quad(x0, y0, x1, y1, color, width, height, z);
  return {quad[0], quad[1], quad[2], quad[5]};
}

std::vector<std::string> Rows(UINT height, std::string_view row) { return std::vector<std::string>(height, std::string(row)); }

int CountPixels(const std::vector<uint8_t>& rgba8, uint32_t value) {
  int count = 0;
  for (size_t i = 0; i + 4 <= rgba8.size(); i += 4) {
    uint32_t p;
    std::memcpy(&p, rgba8.data() + i, 4);
    count += p == value;
  }
  return count;
}

void RhiGpuTest::UseColorPipeline() {
  static const INPUT_ELEMENT_DESC kElements[] = {
      {"POSITION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
      {"COLOR", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0},
  };
  if (!colorVS_) {
    colorVS_ = VSWithLayout(kColorVS, kElements, 2, &colorLayout_);
    colorPS_ = PS(kColorPS);
  }
  context->IASetInputLayout(colorLayout_.Get());
  context->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  context->VSSetShader(colorVS_.Get(), nullptr, 0);
  context->PSSetShader(colorPS_.Get(), nullptr, 0);
}

void RhiGpuTest::BindTarget(RenderTargetView* rtv, UINT width, UINT height, DepthStencilView* dsv) {
  context->OMSetRenderTargets(rtv ? 1 : 0, &rtv, dsv);
  SetViewport(width, height);
}

ComPtr<Buffer> RhiGpuTest::VertexBuffer(const std::vector<Vertex>& vertices) {
  return MakeBuffer(BIND_VERTEX_BUFFER, vertices.data(), static_cast<UINT>(vertices.size() * sizeof(Vertex)),
                    USAGE_IMMUTABLE);
}

void RhiGpuTest::DrawVertices(const std::vector<Vertex>& vertices) {
  ComPtr<Buffer> vb = VertexBuffer(vertices);
  const UINT stride = sizeof(Vertex), offset = 0;
  Buffer* buffers[] = {vb.Get()};
  context->IASetVertexBuffers(0, 1, buffers, &stride, &offset);
  context->Draw(static_cast<UINT>(vertices.size()), 0);
}

void RhiGpuTest::Clear(RenderTargetView* rtv, Color color) {
  const FLOAT rgba[4] = {color.r, color.g, color.b, color.a};
  context->ClearRenderTargetView(rtv, rgba);
}

ComPtr<VertexShader> RhiGpuTest::VSWithLayout(std::string_view source, const INPUT_ELEMENT_DESC* elements, UINT count,
                                              ComPtr<InputLayout>* layout) {
  std::vector<uint32_t> code = CompileHlsl(source, "main", "vs_5_0");
  ComPtr<VertexShader> shader;
  EXPECT_EQ(device->CreateVertexShader(code.data(), code.size() * 4, nullptr, shader.GetAddressOf()), S_OK);
  EXPECT_EQ(device->CreateInputLayout(elements, count, code.data(), code.size() * 4, layout->ReleaseAndGetAddressOf()),
            S_OK);
  return shader;
}

RhiGpuTest::DepthTarget RhiGpuTest::MakeDepthTarget(UINT width, UINT height, DXGI_FORMAT format, UINT samples) {
  TEXTURE2D_DESC desc{};
  desc.Width = width;
  desc.Height = height;
  desc.MipLevels = 1;
  desc.ArraySize = 1;
  desc.Format = format;
  desc.SampleDesc.Count = samples;
  desc.Usage = USAGE_DEFAULT;
  desc.BindFlags = BIND_DEPTH_STENCIL;
  DepthTarget target;
  EXPECT_EQ(device->CreateTexture2D(&desc, nullptr, target.texture.GetAddressOf()), S_OK);
  EXPECT_EQ(device->CreateDepthStencilView(target.texture.Get(), nullptr, target.dsv.GetAddressOf()), S_OK);
  return target;
}

ComPtr<Texture2D> RhiGpuTest::MakeTexture(UINT width, UINT height, DXGI_FORMAT format, UINT bindFlags, UINT samples) {
  TEXTURE2D_DESC desc{width, height, 1, 1, format, {samples, 0}, USAGE_DEFAULT, bindFlags, 0, 0};
  ComPtr<Texture2D> texture;
  EXPECT_EQ(device->CreateTexture2D(&desc, nullptr, texture.GetAddressOf()), S_OK);
  return texture;
}

void RhiGpuTest::DrawFullScreen(PixelShader* ps) {
  if (!fullScreenVS_)
    fullScreenVS_ = VS(R"(float4 main(uint id : SV_VertexID) : SV_Position {
        return float4(float(id & 1) * 4 - 1, 1 - float(id & 2) * 2, 0.5, 1); })");
  context->IASetInputLayout(nullptr);
  context->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  context->VSSetShader(fullScreenVS_.Get(), nullptr, 0);
  context->PSSetShader(ps, nullptr, 0);
  context->Draw(3, 0);
}

std::vector<float> RhiGpuTest::ReadSamples(ShaderResourceView* srv, UINT width, UINT height, UINT samples,
                                           const char* type) {
  // Sample s of pixel (x, y) lands in texel (x * samples + s, y) of a float4 target.
  ComPtr<Texture2D> out = MakeTexture(width * samples, height, DXGI_FORMAT_R32G32B32A32_FLOAT, BIND_RENDER_TARGET);
  ComPtr<RenderTargetView> rtv;
  EXPECT_EQ(device->CreateRenderTargetView(out.Get(), nullptr, rtv.GetAddressOf()), S_OK);
  const std::string source = std::string("Texture2DMS<") + type + "> S : register(t0);\n" +
                             "float4 main(float4 pos : SV_Position) : SV_Target {\n"
                             "  uint x = uint(pos.x);\n"
                             "  return (float4)S.Load(int2(x / " + std::to_string(samples) + ", pos.y), x % " +
                             std::to_string(samples) + ");\n}\n";
  ComPtr<PixelShader> ps = PS(source);
  context->ClearState();
  BindTarget(rtv.Get(), width * samples, height);
  context->PSSetShaderResources(0, 1, &srv);
  DrawFullScreen(ps.Get());
  context->ClearState();
  return ReadFloats(out.Get());
}

std::vector<float> RhiGpuTest::ReadFloats(Texture2D* texture) {
  std::vector<uint8_t> bytes = ReadTexture(texture);
  std::vector<float> values(bytes.size() / sizeof(float));
  std::memcpy(values.data(), bytes.data(), values.size() * sizeof(float));
  return values;
}

ComPtr<BlendState> RhiGpuTest::Blend(const BLEND_DESC& desc) {
  ComPtr<BlendState> state;
  EXPECT_EQ(device->CreateBlendState(&desc, state.GetAddressOf()), S_OK);
  return state;
}

ComPtr<DepthStencilState> RhiGpuTest::DepthStencil(const DEPTH_STENCIL_DESC& desc) {
  ComPtr<DepthStencilState> state;
  EXPECT_EQ(device->CreateDepthStencilState(&desc, state.GetAddressOf()), S_OK);
  return state;
}

ComPtr<RasterizerState> RhiGpuTest::Rasterizer(const RASTERIZER_DESC& desc) {
  ComPtr<RasterizerState> state;
  EXPECT_EQ(device->CreateRasterizerState(&desc, state.GetAddressOf()), S_OK);
  return state;
}

ComPtr<SamplerState> RhiGpuTest::PointSampler() {
  SAMPLER_DESC desc;
  desc.Filter = FILTER_MIN_MAG_MIP_POINT;
  ComPtr<SamplerState> state;
  EXPECT_EQ(device->CreateSamplerState(&desc, state.GetAddressOf()), S_OK);
  return state;
}

}  // namespace rhi_test
