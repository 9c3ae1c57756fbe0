// demo: a small lit, textured, depth-tested scene drawn through the D3D11-shaped RHI.
//
//   demo                         GLFW window + rhi::SwapChain (resizable; minimising pauses)
//   demo --headless --out DIR    one frame into an offscreen target -> DIR/demo_scene.png
//   demo --headless --bench N    N frames, then a timing table (CPU and GPU time per frame)
//
// Rendering: 640x360 (window: the framebuffer size), R8G8B8A8_UNORM_SRGB colour with
// 4x MSAA (falls back to 1 sample when the device refuses it) resolved with
// ResolveSubresource, D32_FLOAT depth with the default depth-stencil state, one
// directional light + ambient (Lambert), a procedurally generated sRGB tile texture
// with a full CPU-generated mip chain, a linear/wrap sampler.
//
// Matrices: GLM, left-handed (lookAtLH / perspectiveLH_ZO, depth 0..1 as in D3D).
// The cbuffer uses HLSL's default column_major packing, so GLM's column-major memory
// is uploaded unchanged and the shader multiplies column vectors: mul(M, v).
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#define GLM_FORCE_DEPTH_ZERO_TO_ONE
#define GLM_FORCE_LEFT_HANDED
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cli_args.h"
#include "fx/shader_directory.h"
#include "hlsl/hlsl_compiler.h"
#include "rhi/capture.h"
#include "rhi/query_wait.h"
#include "rhi/rhi.h"
#include "rhi/swap_chain.h"
#include "scene_params.h"

using rhi::ComPtr;
using rhi::INT;
using rhi::UINT;

namespace {

// ---------------------------------------------------------------------------
// Failure handling: every failure prints a reason and exits non-zero.

[[noreturn]] void Fail(const std::string& what) {
  std::fprintf(stderr, "demo: %s\n", what.c_str());
  std::exit(1);
}

void Check(rhi::HRESULT hr, const char* what) {
  if (rhi::FAILED(hr)) {
    char buffer[256];
    std::snprintf(buffer, sizeof buffer, "%s failed (HRESULT 0x%08X)", what, static_cast<unsigned>(hr));
    Fail(buffer);
  }
}

int gErrorMessages = 0;  // RHI error messages (refusals, validation errors) seen so far

// ---------------------------------------------------------------------------
// Shaders: read from shaders_hlsl/ at runtime, compiled in-process.

std::vector<uint32_t> Compile(const std::string& path, const char* entry, const char* profile) {
  hlsl::CompileResult result = hlsl::CompileHlslFile(path, entry, profile);
  if (!result.ok) {
    // FormatErrors gives "file:line:column: error: message" lines.
    std::fprintf(stderr, "%s", result.FormatErrors().c_str());
    Fail(std::string("compiling ") + entry + " (" + profile + ") failed");
  }
  return result.spirv;
}

// ---------------------------------------------------------------------------
// Geometry

struct Vertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec2 uv;
};

struct Mesh {
  std::vector<Vertex> vertices;
  std::vector<uint16_t> indices;
};

// One quad with outward normal n, centred at c, half-extents h along its two axes.
// D3D11's default rasterizer culls back faces with clockwise = front. Viewed from
// outside in this left-handed, y-up world, corners c-u-v, c-u+v, c+u+v, c+u-v with
// u x v = -n run clockwise on screen, so those are the triangles' orders.
void AddQuad(Mesh& mesh, glm::vec3 c, glm::vec3 n, glm::vec3 a, float hu, float hv, float uvScale) {
  glm::vec3 u = a;                  // first axis
  glm::vec3 v = glm::cross(a, n);   // u x v = a x (a x n) = -n for unit a perpendicular to n
  const auto base = static_cast<uint16_t>(mesh.vertices.size());
  const glm::vec2 uvs[4] = {{0, 1}, {0, 0}, {1, 0}, {1, 1}};
  const float su[4] = {-1, -1, 1, 1}, sv[4] = {-1, 1, 1, -1};
  for (int i = 0; i < 4; ++i)
    mesh.vertices.push_back({c + su[i] * hu * u + sv[i] * hv * v, n, uvs[i] * uvScale});
  for (uint16_t i : {0, 1, 2, 0, 2, 3}) mesh.indices.push_back(static_cast<uint16_t>(base + i));
}

Mesh MakeCube() {
  Mesh mesh;
  const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (glm::vec3 n : normals) {
    glm::vec3 a = std::abs(n.y) > 0.5f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    AddQuad(mesh, 0.5f * n, n, a, 0.5f, 0.5f, 1.0f);
  }
  return mesh;
}

Mesh MakeGround() {
  Mesh mesh;
  AddQuad(mesh, {0, 0, 0}, {0, 1, 0}, {1, 0, 0}, demo::kGroundSize / 2, demo::kGroundSize / 2,
          demo::kGroundRepeat);
  return mesh;
}

// ---------------------------------------------------------------------------
// The procedural texture and its mip chain (CPU box filter in linear light).

float SrgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }
float LinearToSrgb(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

std::vector<uint8_t> MakeTileTexture() {
  const uint32_t size = demo::kTextureSize, cell = size / demo::kCheckerCells;
  std::vector<uint8_t> texels(size * size * 4);
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) {
      const uint32_t cx = x / cell, cy = y / cell;
      const bool mortar = (x % cell) < demo::kMortarTexels / 2 || (x % cell) >= cell - demo::kMortarTexels / 2 ||
                          (y % cell) < demo::kMortarTexels / 2 || (y % cell) >= cell - demo::kMortarTexels / 2;
      const uint8_t* rgb = mortar ? demo::kMortar : ((cx + cy) % 2 == 0 ? demo::kCheckerA : demo::kCheckerB);
      uint8_t* t = &texels[(y * size + x) * 4];
      t[0] = rgb[0], t[1] = rgb[1], t[2] = rgb[2], t[3] = 255;
    }
  }
  return texels;
}

// Halves an sRGB RGBA8 image (2x2 box filter, averaged in linear light).
std::vector<uint8_t> Downsample(const std::vector<uint8_t>& src, uint32_t w, uint32_t h) {
  const uint32_t dw = std::max(1u, w / 2), dh = std::max(1u, h / 2);
  std::vector<uint8_t> dst(dw * dh * 4);
  for (uint32_t y = 0; y < dh; ++y) {
    for (uint32_t x = 0; x < dw; ++x) {
      for (int c = 0; c < 4; ++c) {
        float sum = 0;
        for (uint32_t dy = 0; dy < 2; ++dy) {
          for (uint32_t dx = 0; dx < 2; ++dx) {
            const uint32_t sx = std::min(w - 1, x * 2 + dx), sy = std::min(h - 1, y * 2 + dy);
            const float v = src[(sy * w + sx) * 4 + c] / 255.0f;
            sum += c == 3 ? v : SrgbToLinear(v);
          }
        }
        const float avg = sum / 4;
        dst[(y * dw + x) * 4 + c] = static_cast<uint8_t>(std::lround((c == 3 ? avg : LinearToSrgb(avg)) * 255));
      }
    }
  }
  return dst;
}

// ---------------------------------------------------------------------------
// The renderer

struct alignas(16) SceneConstants {
  glm::mat4 world, view, proj;  // column-major, as the HLSL cbuffer's default packing
  glm::vec4 lightDir, lightColor, ambient, tint;
};
static_assert(sizeof(SceneConstants) == 3 * 64 + 4 * 16, "must match the HLSL cbuffer layout");

struct DrawItem {
  UINT indexCount, startIndex;
  INT baseVertex;
  glm::mat4 world;
  glm::vec3 tint;
};

class Demo {
 public:
  explicit Demo(rhi::Device* device, rhi::DeviceContext* context) : device_(device), context_(context) {}

  void Initialize() {
    const std::string shaderPath = fx::ShaderDirectory() + "/scene.hlsl";
    std::vector<uint32_t> vsCode = Compile(shaderPath, "VSMain", "vs_5_0");
    std::vector<uint32_t> psCode = Compile(shaderPath, "PSMain", "ps_5_0");
    Check(device_->CreateVertexShader(vsCode.data(), vsCode.size() * 4, nullptr, vs_.GetAddressOf()),
          "CreateVertexShader");
    Check(device_->CreatePixelShader(psCode.data(), psCode.size() * 4, nullptr, ps_.GetAddressOf()),
          "CreatePixelShader");
    const rhi::INPUT_ELEMENT_DESC layout[] = {
        {"POSITION", 0, rhi::DXGI_FORMAT_R32G32B32_FLOAT, 0, offsetof(Vertex, position), rhi::INPUT_PER_VERTEX_DATA, 0},
        {"NORMAL", 0, rhi::DXGI_FORMAT_R32G32B32_FLOAT, 0, offsetof(Vertex, normal), rhi::INPUT_PER_VERTEX_DATA, 0},
        {"TEXCOORD", 0, rhi::DXGI_FORMAT_R32G32_FLOAT, 0, offsetof(Vertex, uv), rhi::INPUT_PER_VERTEX_DATA, 0},
    };
    Check(device_->CreateInputLayout(layout, 3, vsCode.data(), vsCode.size() * 4, inputLayout_.GetAddressOf()),
          "CreateInputLayout");

    // One vertex/index buffer for everything: the ground, then the cube.
    Mesh ground = MakeGround(), cube = MakeCube();
    Mesh all = ground;
    all.vertices.insert(all.vertices.end(), cube.vertices.begin(), cube.vertices.end());
    all.indices.insert(all.indices.end(), cube.indices.begin(), cube.indices.end());
    rhi::BUFFER_DESC vbDesc{static_cast<UINT>(all.vertices.size() * sizeof(Vertex)), rhi::USAGE_IMMUTABLE,
                            rhi::BIND_VERTEX_BUFFER, 0, 0, 0};
    rhi::SUBRESOURCE_DATA vbData{all.vertices.data(), 0, 0};
    Check(device_->CreateBuffer(&vbDesc, &vbData, vertexBuffer_.GetAddressOf()), "CreateBuffer(vertices)");
    rhi::BUFFER_DESC ibDesc{static_cast<UINT>(all.indices.size() * sizeof(uint16_t)), rhi::USAGE_IMMUTABLE,
                            rhi::BIND_INDEX_BUFFER, 0, 0, 0};
    rhi::SUBRESOURCE_DATA ibData{all.indices.data(), 0, 0};
    Check(device_->CreateBuffer(&ibDesc, &ibData, indexBuffer_.GetAddressOf()), "CreateBuffer(indices)");

    const UINT groundIndices = static_cast<UINT>(ground.indices.size());
    const INT cubeBase = static_cast<INT>(ground.vertices.size());
    const UINT cubeIndices = static_cast<UINT>(cube.indices.size());
    items_.push_back({groundIndices, 0, 0, glm::mat4(1.0f), glm::make_vec3(demo::kGroundTint)});
    auto cubeAt = [&](glm::vec3 position, float size, float yawDegrees, glm::vec3 tint) {
      glm::mat4 world = glm::translate(glm::mat4(1.0f), position + glm::vec3(0, size / 2, 0));
      world = glm::rotate(world, glm::radians(yawDegrees), glm::vec3(0, 1, 0));
      world = glm::scale(world, glm::vec3(size));
      items_.push_back({cubeIndices, groundIndices, cubeBase, world, tint});
    };
    cubeAt({-3.0f, 0, 1.0f}, 2.0f, 20.0f, {1.0f, 0.55f, 0.5f});
    cubeAt({0.5f, 0, 3.0f}, 2.5f, -35.0f, {0.55f, 1.0f, 0.6f});
    cubeAt({3.2f, 0, -0.5f}, 1.5f, 45.0f, {0.55f, 0.65f, 1.0f});

    // Constant buffer: DYNAMIC, rewritten (WRITE_DISCARD) per draw.
    rhi::BUFFER_DESC cbDesc{sizeof(SceneConstants), rhi::USAGE_DYNAMIC, rhi::BIND_CONSTANT_BUFFER,
                            rhi::CPU_ACCESS_WRITE, 0, 0};
    Check(device_->CreateBuffer(&cbDesc, nullptr, constants_.GetAddressOf()), "CreateBuffer(constants)");

    // Texture with every mip level given as initial data (generated on the CPU).
    std::vector<std::vector<uint8_t>> levels{MakeTileTexture()};
    uint32_t w = demo::kTextureSize, h = demo::kTextureSize;
    while (w > 1 || h > 1) {
      levels.push_back(Downsample(levels.back(), w, h));
      w = std::max(1u, w / 2), h = std::max(1u, h / 2);
    }
    std::vector<rhi::SUBRESOURCE_DATA> init;
    for (size_t i = 0; i < levels.size(); ++i)
      init.push_back({levels[i].data(), std::max(1u, demo::kTextureSize >> i) * 4, 0});
    rhi::TEXTURE2D_DESC texDesc{};
    texDesc.Width = texDesc.Height = demo::kTextureSize;
    texDesc.MipLevels = static_cast<UINT>(levels.size());
    texDesc.ArraySize = 1;
    texDesc.Format = rhi::DXGI_FORMAT_R8G8B8A8_UNORM_SRGB;
    texDesc.SampleDesc = {1, 0};
    texDesc.Usage = rhi::USAGE_IMMUTABLE;
    texDesc.BindFlags = rhi::BIND_SHADER_RESOURCE;
    Check(device_->CreateTexture2D(&texDesc, init.data(), texture_.GetAddressOf()), "CreateTexture2D(albedo)");
    Check(device_->CreateShaderResourceView(texture_.Get(), nullptr, textureView_.GetAddressOf()),
          "CreateShaderResourceView");

    rhi::SAMPLER_DESC samplerDesc;  // D3D11 defaults, then linear + wrap
    samplerDesc.Filter = rhi::FILTER_MIN_MAG_MIP_LINEAR;
    samplerDesc.AddressU = samplerDesc.AddressV = samplerDesc.AddressW = rhi::TEXTURE_ADDRESS_WRAP;
    Check(device_->CreateSamplerState(&samplerDesc, sampler_.GetAddressOf()), "CreateSamplerState");
    rhi::DEPTH_STENCIL_DESC depthDesc;  // the D3D11 default: LESS, write all
    Check(device_->CreateDepthStencilState(&depthDesc, depthState_.GetAddressOf()), "CreateDepthStencilState");
    rhi::RASTERIZER_DESC rasterDesc;  // the D3D11 default: solid, cull back, clockwise front
    rasterDesc.MultisampleEnable = rhi::TRUE;
    Check(device_->CreateRasterizerState(&rasterDesc, rasterizer_.GetAddressOf()), "CreateRasterizerState");
  }

  // (Re)creates the MSAA colour + depth targets and the single-sample resolve target.
  // `resolveTarget`: a texture to resolve into (the swap chain's back buffer), or null
  // to create an offscreen one.
  void CreateTargets(UINT width, UINT height, rhi::Texture2D* resolveTarget) {
    width_ = width, height_ = height;
    msaaColor_.Reset(), msaaView_.Reset(), depth_.Reset(), depthView_.Reset(), resolved_.Reset();
    rhi::TEXTURE2D_DESC desc{};
    desc.Width = width;
    desc.Height = height;
    desc.MipLevels = 1;
    desc.ArraySize = 1;
    desc.Format = rhi::DXGI_FORMAT_R8G8B8A8_UNORM_SRGB;
    desc.Usage = rhi::USAGE_DEFAULT;
    desc.BindFlags = rhi::BIND_RENDER_TARGET;
    if (resolveTarget) {
      resolved_ = resolveTarget;
    } else {
      desc.SampleDesc = {1, 0};
      desc.BindFlags = rhi::BIND_RENDER_TARGET | rhi::BIND_SHADER_RESOURCE;
      Check(device_->CreateTexture2D(&desc, nullptr, resolved_.GetAddressOf()), "CreateTexture2D(resolve target)");
    }
    desc.BindFlags = rhi::BIND_RENDER_TARGET;
    desc.SampleDesc = {samples_, 0};
    if (samples_ > 1 && rhi::FAILED(device_->CreateTexture2D(&desc, nullptr, msaaColor_.GetAddressOf()))) {
      std::fprintf(stderr, "demo: 4x MSAA colour target refused; rendering without MSAA\n");
      --gErrorMessages;  // the refusal just reported is expected and handled
      samples_ = 1;
    }
    if (samples_ > 1) {
      Check(device_->CreateRenderTargetView(msaaColor_.Get(), nullptr, msaaView_.GetAddressOf()),
            "CreateRenderTargetView(msaa)");
    } else {
      Check(device_->CreateRenderTargetView(resolved_.Get(), nullptr, msaaView_.GetAddressOf()),
            "CreateRenderTargetView");
    }
    desc.Format = rhi::DXGI_FORMAT_D32_FLOAT;
    desc.BindFlags = rhi::BIND_DEPTH_STENCIL;
    desc.SampleDesc = {samples_, 0};
    Check(device_->CreateTexture2D(&desc, nullptr, depth_.GetAddressOf()), "CreateTexture2D(depth)");
    Check(device_->CreateDepthStencilView(depth_.Get(), nullptr, depthView_.GetAddressOf()),
          "CreateDepthStencilView");
  }

  void ReleaseTargets() {
    msaaColor_.Reset(), msaaView_.Reset(), depth_.Reset(), depthView_.Reset(), resolved_.Reset();
  }

  void Render() {
    rhi::DeviceContext* ctx = context_;
    ctx->ClearRenderTargetView(msaaView_.Get(), demo::kClearColor);
    ctx->ClearDepthStencilView(depthView_.Get(), rhi::CLEAR_DEPTH, 1.0f, 0);

    rhi::RenderTargetView* rtv = msaaView_.Get();
    ctx->OMSetRenderTargets(1, &rtv, depthView_.Get());
    ctx->OMSetDepthStencilState(depthState_.Get(), 0);
    ctx->OMSetBlendState(nullptr, nullptr, rhi::DEFAULT_SAMPLE_MASK);
    rhi::VIEWPORT viewport{0, 0, static_cast<float>(width_), static_cast<float>(height_), 0, 1};
    ctx->RSSetViewports(1, &viewport);
    ctx->RSSetState(rasterizer_.Get());

    ctx->IASetInputLayout(inputLayout_.Get());
    rhi::Buffer* vb = vertexBuffer_.Get();
    const UINT stride = sizeof(Vertex), offset = 0;
    ctx->IASetVertexBuffers(0, 1, &vb, &stride, &offset);
    ctx->IASetIndexBuffer(indexBuffer_.Get(), rhi::DXGI_FORMAT_R16_UINT, 0);
    ctx->IASetPrimitiveTopology(rhi::PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    ctx->VSSetShader(vs_.Get(), nullptr, 0);
    ctx->PSSetShader(ps_.Get(), nullptr, 0);
    rhi::Buffer* cb = constants_.Get();
    ctx->VSSetConstantBuffers(0, 1, &cb);
    ctx->PSSetConstantBuffers(0, 1, &cb);
    rhi::ShaderResourceView* srv = textureView_.Get();
    ctx->PSSetShaderResources(0, 1, &srv);
    rhi::SamplerState* sampler = sampler_.Get();
    ctx->PSSetSamplers(0, 1, &sampler);

    SceneConstants constants{};
    constants.view = glm::lookAtLH(glm::make_vec3(demo::kEye), glm::make_vec3(demo::kTarget), glm::vec3(0, 1, 0));
    constants.proj = glm::perspectiveLH_ZO(glm::radians(demo::kFovYDegrees),
                                           static_cast<float>(width_) / static_cast<float>(height_), demo::kNear,
                                           demo::kFar);
    constants.lightDir = glm::vec4(glm::normalize(glm::make_vec3(demo::kLightDir)), 0);
    constants.lightColor = glm::vec4(glm::make_vec3(demo::kLightColor), 0);
    constants.ambient = glm::vec4(glm::make_vec3(demo::kAmbient), 0);
    for (const DrawItem& item : items_) {
      constants.world = item.world;
      constants.tint = glm::vec4(item.tint, 1);
      rhi::MAPPED_SUBRESOURCE mapped{};
      Check(ctx->Map(constants_.Get(), 0, rhi::MAP_WRITE_DISCARD, 0, &mapped), "Map(constants)");
      std::memcpy(mapped.pData, &constants, sizeof constants);
      ctx->Unmap(constants_.Get(), 0);
      ctx->DrawIndexed(item.indexCount, item.startIndex, item.baseVertex);
    }

    if (samples_ > 1)
      ctx->ResolveSubresource(resolved_.Get(), 0, msaaColor_.Get(), 0, rhi::DXGI_FORMAT_R8G8B8A8_UNORM_SRGB);
  }

  // Reads the resolved frame back through a STAGING texture; returns tightly packed RGBA8.
  std::vector<uint8_t> ReadBack() {
    std::vector<uint8_t> pixels;
    Check(rhi::CaptureTexture2D(device_, context_, resolved_.Get(), 0, &pixels), "CaptureTexture2D");
    return pixels;
  }

  UINT samples() const { return samples_; }

 private:
  rhi::Device* device_;
  rhi::DeviceContext* context_;
  ComPtr<rhi::VertexShader> vs_;
  ComPtr<rhi::PixelShader> ps_;
  ComPtr<rhi::InputLayout> inputLayout_;
  ComPtr<rhi::Buffer> vertexBuffer_, indexBuffer_, constants_;
  ComPtr<rhi::Texture2D> texture_;
  ComPtr<rhi::ShaderResourceView> textureView_;
  ComPtr<rhi::SamplerState> sampler_;
  ComPtr<rhi::DepthStencilState> depthState_;
  ComPtr<rhi::RasterizerState> rasterizer_;
  std::vector<DrawItem> items_;

  UINT width_ = 0, height_ = 0, samples_ = 4;
  ComPtr<rhi::Texture2D> msaaColor_, depth_, resolved_;
  ComPtr<rhi::RenderTargetView> msaaView_;
  ComPtr<rhi::DepthStencilView> depthView_;
};

// ---------------------------------------------------------------------------
// Modes

double Median(std::vector<double> values) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

int RunBench(rhi::Device* device, rhi::DeviceContext* ctx, Demo& demo, int frames) {
  rhi::QUERY_DESC disjointDesc{rhi::QUERY_TIMESTAMP_DISJOINT, 0}, tsDesc{rhi::QUERY_TIMESTAMP, 0};
  ComPtr<rhi::Query> disjoint, begin, end;
  Check(device->CreateQuery(&disjointDesc, disjoint.GetAddressOf()), "CreateQuery(TIMESTAMP_DISJOINT)");
  Check(device->CreateQuery(&tsDesc, begin.GetAddressOf()), "CreateQuery(TIMESTAMP)");
  Check(device->CreateQuery(&tsDesc, end.GetAddressOf()), "CreateQuery(TIMESTAMP)");
  std::vector<double> cpuMs, gpuMs;
  int disjointFrames = 0;
  for (int i = 0; i < frames; ++i) {
    const auto start = std::chrono::steady_clock::now();
    ctx->Begin(disjoint.Get());
    ctx->End(begin.Get());
    demo.Render();
    ctx->End(end.Get());
    ctx->End(disjoint.Get());
    ctx->Flush();
    const auto recorded = std::chrono::steady_clock::now();
    // Waiting for the queries also keeps frames from piling up.
    rhi::QUERY_DATA_TIMESTAMP_DISJOINT dj{};
    rhi::UINT64 t0 = 0, t1 = 0;
    Check(rhi::WaitForData(ctx, disjoint.Get(), &dj), "GetData(TIMESTAMP_DISJOINT)");
    Check(rhi::WaitForData(ctx, begin.Get(), &t0), "GetData(TIMESTAMP)");
    Check(rhi::WaitForData(ctx, end.Get(), &t1), "GetData(TIMESTAMP)");
    cpuMs.push_back(std::chrono::duration<double, std::milli>(recorded - start).count());
    if (dj.Disjoint || dj.Frequency == 0) {
      ++disjointFrames;
    } else {
      gpuMs.push_back(1000.0 * static_cast<double>(t1 - t0) / static_cast<double>(dj.Frequency));
    }
  }
  std::printf("%-28s %10s %10s %10s\n", "per frame (ms)", "median", "min", "max");
  auto row = [](const char* name, const std::vector<double>& v) {
    if (v.empty()) {
      std::printf("%-28s %10s\n", name, "n/a");
      return;
    }
    std::printf("%-28s %10.3f %10.3f %10.3f\n", name, Median(v), *std::min_element(v.begin(), v.end()),
                *std::max_element(v.begin(), v.end()));
  };
  row("CPU (record + Flush)", cpuMs);
  row("GPU (TIMESTAMP queries)", gpuMs);
  std::printf("%d frames, %d disjoint, %u samples, %ux%u\n", frames, disjointFrames, demo.samples(), demo::kWidth,
              demo::kHeight);
  return 0;
}

int RunHeadless(rhi::Device* device, rhi::DeviceContext* ctx, const std::string& outDir, int benchFrames) {
  Demo demo(device, ctx);
  demo.Initialize();
  demo.CreateTargets(demo::kWidth, demo::kHeight, nullptr);
  if (benchFrames > 0) RunBench(device, ctx, demo, benchFrames);
  demo.Render();
  std::vector<uint8_t> pixels = demo.ReadBack();
  if (gErrorMessages > 0) Fail("the RHI reported errors (see above)");
  const std::string path = (std::filesystem::path(outDir) / "demo_scene.png").string();
  if (!stbi_write_png(path.c_str(), demo::kWidth, demo::kHeight, 4, pixels.data(), demo::kWidth * 4))
    Fail("cannot write " + path);
  std::printf("wrote %s (%ux%u, %ux MSAA) on %s\n", path.c_str(), demo::kWidth, demo::kHeight, demo.samples(),
              device->GetAdapterName());
  return 0;
}

int RunWindowed(rhi::Device* device, rhi::DeviceContext* ctx, GLFWwindow* window, int maxFrames, bool testResize) {
  Demo demo(device, ctx);
  demo.Initialize();

  int fbWidth = 0, fbHeight = 0;
  glfwGetFramebufferSize(window, &fbWidth, &fbHeight);
  rhi::SWAP_CHAIN_DESC scDesc{};
  scDesc.Width = static_cast<UINT>(std::max(fbWidth, 1));
  scDesc.Height = static_cast<UINT>(std::max(fbHeight, 1));
  scDesc.Format = rhi::DXGI_FORMAT_R8G8B8A8_UNORM_SRGB;
  scDesc.BufferCount = 2;
  ComPtr<rhi::SwapChain> swapChain;
  auto createSurface = [window](void* instance, uint64_t* surface) {
    VkSurfaceKHR created = VK_NULL_HANDLE;
    VkResult result = glfwCreateWindowSurface(static_cast<VkInstance>(instance), window, nullptr, &created);
    *surface = reinterpret_cast<uint64_t>(created);
    return result == VK_SUCCESS;
  };
  Check(rhi::CreateSwapChain(device, &scDesc, createSurface, swapChain.GetAddressOf()), "CreateSwapChain");

  UINT width = scDesc.Width, height = scDesc.Height;
  auto attachBackBuffer = [&] {
    ComPtr<rhi::Texture2D> backBuffer;
    Check(swapChain->GetBuffer(0, backBuffer.GetAddressOf()), "SwapChain::GetBuffer");
    demo.CreateTargets(width, height, backBuffer.Get());
  };
  attachBackBuffer();

  int frames = 0;
  while (!glfwWindowShouldClose(window) && (maxFrames <= 0 || frames < maxFrames)) {
    glfwPollEvents();
    glfwGetFramebufferSize(window, &fbWidth, &fbHeight);
    if (fbWidth == 0 || fbHeight == 0) {  // minimised: nothing to draw into
      glfwWaitEvents();
      continue;
    }
    if (static_cast<UINT>(fbWidth) != width || static_cast<UINT>(fbHeight) != height) {
      width = static_cast<UINT>(fbWidth), height = static_cast<UINT>(fbHeight);
      ctx->OMSetRenderTargets(0, nullptr, nullptr);
      demo.ReleaseTargets();  // DXGI: release every back-buffer reference before ResizeBuffers
      std::printf("resizing to %ux%u\n", width, height);
      Check(swapChain->ResizeBuffers(0, width, height, rhi::DXGI_FORMAT_UNKNOWN, 0), "SwapChain::ResizeBuffers");
      attachBackBuffer();
    }
    demo.Render();
    Check(swapChain->Present(1, 0), "SwapChain::Present");
    ++frames;
    if (testResize && frames == 10) glfwSetWindowSize(window, 800, 450);
    if (testResize && frames == 20) glfwSetWindowSize(window, 320, 180);
    if (gErrorMessages > 0) Fail("the RHI reported errors (see above)");
  }
  demo.ReleaseTargets();
  std::printf("presented %d frames (%ux%u, %ux MSAA) on %s\n", frames, width, height, demo.samples(),
              device->GetAdapterName());
  return 0;
}

// A frame count option's value: 1 to 1,000,000, else a one-line failure.
int FrameCount(const std::string& option, const std::string& text) {
  std::string error;
  std::optional<int64_t> frames = cli::ParseInteger(option, text, 1, 1000000, &error);
  if (!frames) Fail(error);
  return static_cast<int>(*frames);
}

void Usage() {
  std::fprintf(stderr,
               "usage: demo [--headless --out DIR [--bench N]] [--frames N] [--test-resize] [--validation]\n"
               "  --headless     render one frame offscreen and write DIR/demo_scene.png\n"
               "  --bench N      (headless) render N frames first and print a timing table\n"
               "  --frames N     (window) close after N presented frames\n"
               "  --test-resize  (window) resize the window after 10 and 20 frames\n"
               "  --validation   enable the Khronos validation layer\n");
}

}  // namespace

int main(int argc, char** argv) {
  bool headless = false, validation = false, testResize = false;
  std::string outDir = "out";
  int benchFrames = 0, maxFrames = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        Usage();
        Fail(arg + " needs a value");
      }
      return argv[++i];
    };
    if (arg == "--headless") headless = true;
    else if (arg == "--out") outDir = value();
    else if (arg == "--bench") benchFrames = FrameCount(arg, value());
    else if (arg == "--frames") maxFrames = FrameCount(arg, value());
    else if (arg == "--validation") validation = true;
    else if (arg == "--test-resize") testResize = true;
    else if (arg == "--help" || arg == "-h") { Usage(); return 0; }
    else { Usage(); Fail("unknown argument " + arg); }
  }
  if (benchFrames > 0) headless = true;

  rhi::DEVICE_OPTIONS options;
  options.EnableValidation = validation ? rhi::TRUE : rhi::FALSE;
  options.OnMessage = [](rhi::MESSAGE_CATEGORY category, rhi::MESSAGE_SEVERITY severity, const char* text) {
    const bool error = severity <= rhi::MESSAGE_SEVERITY_ERROR;
    if (error) ++gErrorMessages;
    std::fprintf(stderr, "rhi %s%s: %s\n", category == rhi::MESSAGE_CATEGORY_VULKAN_VALIDATION ? "validation " : "",
                 error ? "error" : "warning", text);
  };

  if (headless) {
    // Before the device: Fail exits, and a live device at exit is a leak (./run sanitize).
    if (std::string error; !cli::MakeFolder("--out", outDir, &error)) Fail(error);
    ComPtr<rhi::Device> device;
    ComPtr<rhi::DeviceContext> context;
    Check(rhi::CreateDevice(&options, device.GetAddressOf(), context.GetAddressOf()), "CreateDevice");
    int rc = RunHeadless(device.Get(), context.Get(), outDir, benchFrames);
    context.Reset();
    device.Reset();
    return rc;
  }

  if (!glfwInit()) Fail("glfwInit failed (no display?); use --headless");
  if (!glfwVulkanSupported()) Fail("GLFW found no Vulkan loader");
  uint32_t extensionCount = 0;
  const char** extensions = glfwGetRequiredInstanceExtensions(&extensionCount);
  if (!extensions) Fail("GLFW reports no Vulkan surface extensions for this display");
  options.InstanceExtensions = extensions;
  options.InstanceExtensionCount = extensionCount;
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(demo::kWidth, demo::kHeight, "demo (D3D11 over Vulkan)", nullptr, nullptr);
  if (!window) Fail("glfwCreateWindow failed");
  int rc = 0;
  {
    ComPtr<rhi::Device> device;
    ComPtr<rhi::DeviceContext> context;
    Check(rhi::CreateDevice(&options, device.GetAddressOf(), context.GetAddressOf()), "CreateDevice");
    rc = RunWindowed(device.Get(), context.Get(), window, maxFrames, testResize);
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  return rc;
}
