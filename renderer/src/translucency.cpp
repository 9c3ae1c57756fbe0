#include "renderer/translucency.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <numeric>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "hlsl/hlsl_compiler.h"
#include "renderer/oit_blend_tables.h"

namespace renderer {

using namespace rhi;

namespace {

const std::string kShaderDir = PROJECT_SOURCE_ROOT "/shaders_hlsl";

bool Compile(const char* file, const char* entry, const char* profile, std::vector<uint32_t>* spirv,
             std::string* error) {
  const std::string path = kShaderDir + "/" + file;
  std::ifstream stream(path);
  if (!stream) {
    *error = path + ": cannot open";
    return false;
  }
  std::stringstream text;
  text << stream.rdbuf();
  hlsl::CompileRequest request{text.str(), path, entry, profile, {}, {kShaderDir}};
  hlsl::CompileResult result = hlsl::CompileHlsl(request);
  if (!result.ok) {
    *error = std::string(file) + ":" + entry + ": " + result.FormatErrors();
    return false;
  }
  *spirv = std::move(result.spirv);
  return true;
}

// Deterministic randomness: a hash of (seed, stream, index) -> [0, 1).
float Random(uint32_t seed, uint32_t stream, uint32_t index) {
  uint32_t x = ParticleHash(seed * 0x9E3779B9u ^ ParticleHash(stream * 0x85EBCA6Bu + index));
  x = ParticleHash(x + index);
  return (x >> 8) * (1.0f / 16777216.0f);
}

struct OpaqueVertex {
  glm::vec3 position, normal, color;
};

struct ShardVertex {
  glm::vec3 position, normal;
};

struct ShardInstance {
  glm::vec4 world[4];  // columns
  glm::vec4 tint;      // rgb transmission, a alpha
};
static_assert(sizeof(ShardInstance) == 80);

struct OpaqueParams {
  glm::mat4 viewProj;
  glm::vec3 lightDir;
  float ambient;
};

struct SmokeParams {
  glm::mat4 viewProj;
  glm::vec3 eye;
  float seconds;
  glm::vec3 acceleration;
  float size;
  glm::vec3 lightDir;
  float pad;
};

struct ShardParams {
  glm::mat4 viewProj;
  glm::vec3 eye;
  float surfaceTint;
  glm::vec3 lightDir;
  float pad;
};

struct ParticleData {
  float origin[3];
  float velocity[3];
  uint32_t seedAge[2];
  uint32_t kindLife[2];
};
static_assert(sizeof(ParticleData) == kParticleStride);

const glm::vec3 kLightDir = glm::normalize(glm::vec3(-0.4f, 0.8f, -0.45f));

void AddQuad(std::vector<OpaqueVertex>* v, glm::vec3 o, glm::vec3 u, glm::vec3 w, glm::vec3 color) {
  glm::vec3 n = glm::normalize(glm::cross(w, u));  // left-handed: u right, w up -> normal towards the viewer
  OpaqueVertex a{o, n, color}, b{o + u, n, color}, c{o + u + w, n, color}, d{o + w, n, color};
  v->insert(v->end(), {a, b, c, a, c, d});
}

void AddBox(std::vector<OpaqueVertex>* v, glm::vec3 lo, glm::vec3 hi, glm::vec3 color) {
  glm::vec3 s = hi - lo;
  glm::vec3 X{s.x, 0, 0}, Y{0, s.y, 0}, Z{0, 0, s.z};
  AddQuad(v, lo, X, Y, color);                        // -z
  AddQuad(v, lo + X + Z, -X, Y, color);               // +z
  AddQuad(v, lo + Z, -Z, Y, color);                   // -x
  AddQuad(v, lo + X, Z, Y, color);                    // +x
  AddQuad(v, lo + Y, X, Z, color);                    // +y
  AddQuad(v, lo + Z, X, -Z, color);                   // -y
}

std::vector<OpaqueVertex> OpaqueScene(bool neutral) {
  std::vector<OpaqueVertex> v;
  const glm::vec3 palette[8] = {{0.9f, 0.15f, 0.12f}, {0.95f, 0.55f, 0.1f}, {0.95f, 0.9f, 0.2f}, {0.2f, 0.75f, 0.25f},
                                {0.15f, 0.75f, 0.85f}, {0.15f, 0.3f, 0.9f},  {0.6f, 0.2f, 0.8f},  {0.95f, 0.95f, 0.95f}};
  const glm::vec3 grey{0.6f, 0.6f, 0.6f};
  for (int i = 0; i < 20; ++i)  // the back wall: vertical stripes
    AddQuad(&v, {-10.0f + i, 0, 4.5f}, {1, 0, 0}, {0, 9, 0}, neutral ? grey : palette[i % 8]);
  for (int i = 0; i < 10; ++i)  // the floor: a checker of bands
    for (int j = 0; j < 8; ++j) {
      glm::vec3 c = ((i + j) & 1) ? glm::vec3(0.35f) : glm::vec3(0.55f);
      AddQuad(&v, {-10.0f + 2 * i, 0, 4.5f - 2 * (j + 1)}, {2, 0, 0}, {0, 0, 2}, neutral ? grey : c);
    }
  struct Box {
    glm::vec3 lo, hi;
    int color;
  } boxes[] = {{{-4.0f, 0, 2.0f}, {-2.8f, 1.2f, 3.2f}, 0}, {{2.2f, 0, 2.4f}, {3.8f, 1.6f, 4.0f}, 5},
               {{-0.6f, 0, 3.2f}, {0.6f, 0.8f, 4.2f}, 2},  {{-2.2f, 0, -1.5f}, {-1.4f, 0.6f, -0.7f}, 3},
               {{1.2f, 0, -0.9f}, {1.9f, 2.4f, -0.2f}, 6}};
  for (const Box& b : boxes) AddBox(&v, b.lo, b.hi, neutral ? grey : palette[b.color]);
  return v;
}

// An irregular shard: a jittered hexagon pushed into a thin double pyramid, flat-shaded.
std::vector<ShardVertex> ShardMesh(uint32_t seed) {
  constexpr int kSides = 6;
  glm::vec3 rim[kSides];
  for (int i = 0; i < kSides; ++i) {
    float angle = 6.2831853f * (i + 0.6f * (Random(seed, 10, i) - 0.5f)) / kSides;
    float radius = 0.5f + 0.5f * Random(seed, 11, i);
    rim[i] = {radius * std::cos(angle), radius * std::sin(angle) * 1.4f, 0.05f * (Random(seed, 12, i) - 0.5f)};
  }
  const glm::vec3 front{0.1f, 0.05f, 0.12f}, back{-0.05f, 0.1f, -0.08f};
  std::vector<ShardVertex> v;
  for (int i = 0; i < kSides; ++i) {
    glm::vec3 a = rim[i], b = rim[(i + 1) % kSides];
    for (glm::vec3 apex : {front, back}) {
      glm::vec3 n = glm::normalize(glm::cross(b - a, apex - a));
      v.push_back({a, n});
      v.push_back({b, n});
      v.push_back({apex, n});
    }
  }
  return v;
}

std::vector<ShardInstance> ShardInstances(const TranslucencySettings& s) {
  const glm::vec3 tints[6] = {{1.0f, 0.2f, 0.15f}, {0.2f, 0.95f, 0.3f}, {0.2f, 0.4f, 1.0f},
                              {1.0f, 0.75f, 0.15f}, {0.2f, 0.9f, 0.95f}, {0.95f, 0.25f, 0.9f}};
  std::vector<ShardInstance> out(s.shardCount);
  for (uint32_t i = 0; i < s.shardCount; ++i) {
    auto r = [&](uint32_t stream) { return Random(s.seed, 100 + stream, i); };
    glm::vec3 position{-3.5f + 7.0f * r(0), 0.2f + 3.6f * r(1), -2.5f + 5.0f * r(2)};
    glm::vec3 axis = glm::normalize(glm::vec3(r(3) - 0.5f, r(4) - 0.5f, r(5) - 0.5f) + glm::vec3(1e-3f));
    float angle = 6.2831853f * r(6);
    float scale = 0.12f + 0.18f * r(7);
    glm::mat4 world = glm::translate(glm::mat4(1.0f), position) * glm::rotate(glm::mat4(1.0f), angle, axis) *
                      glm::scale(glm::mat4(1.0f), glm::vec3(scale));
    for (int c = 0; c < 4; ++c) out[i].world[c] = world[c];
    glm::vec3 tint = s.shardsAllRed ? glm::vec3(1.0f, 0.15f, 0.15f) : tints[std::min(5u, uint32_t(r(8) * 6))];
    out[i].tint = glm::vec4(tint, 0.2f + 0.2f * r(9));
  }
  return out;
}

// The puff: alpha = density (a soft disc with value noise), rgb = a normal map of a
// bumpy hemisphere (n * 0.5 + 0.5, y up in texture space).
std::vector<uint8_t> PuffTexels(uint32_t size, uint32_t seed) {
  auto noise = [&](float x, float y) {  // value noise on an 8x8 lattice
    int xi = int(std::floor(x)), yi = int(std::floor(y));
    float fx = x - xi, fy = y - yi;
    auto at = [&](int a, int b) { return Random(seed, 200, uint32_t((a & 7) * 8 + (b & 7))); };
    fx = fx * fx * (3 - 2 * fx), fy = fy * fy * (3 - 2 * fy);
    float top = at(xi, yi) * (1 - fx) + at(xi + 1, yi) * fx;
    float bottom = at(xi, yi + 1) * (1 - fx) + at(xi + 1, yi + 1) * fx;
    return top * (1 - fy) + bottom * fy;
  };
  std::vector<uint8_t> texels(size * size * 4);
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) {
      float dx = (x + 0.5f) / size * 2 - 1, dy = (y + 0.5f) / size * 2 - 1;
      float r = std::sqrt(dx * dx + dy * dy);
      float u = (x + 0.5f) / size * 8, v = (y + 0.5f) / size * 8;
      float bump = noise(u, v);
      float density = std::clamp((1.0f - r) * (0.6f + 0.8f * bump), 0.0f, 1.0f);
      float e = 0.05f;
      float gx = (noise(u + e, v) - noise(u - e, v)) / (2 * e), gy = (noise(u, v + e) - noise(u, v - e)) / (2 * e);
      glm::vec3 n{dx - 0.15f * gx, -(dy - 0.15f * gy), std::sqrt(std::max(0.0f, 1.0f - std::min(1.0f, r * r))) + 0.3f};
      n = glm::normalize(n);
      uint8_t* t = &texels[(y * size + x) * 4];
      t[0] = uint8_t(std::lround((n.x * 0.5f + 0.5f) * 255));
      t[1] = uint8_t(std::lround((n.y * 0.5f + 0.5f) * 255));
      t[2] = uint8_t(std::lround((n.z * 0.5f + 0.5f) * 255));
      t[3] = uint8_t(std::lround(density * density * 255));
    }
  return texels;
}

template <class T>
void Upload(DeviceContext* context, Buffer* buffer, const T& value) {
  MAPPED_SUBRESOURCE mapped;
  if (SUCCEEDED(context->Map(buffer, 0, MAP_WRITE_DISCARD, 0, &mapped))) {
    std::memcpy(mapped.pData, &value, sizeof value);
    context->Unmap(buffer, 0);
  }
}

}  // namespace

const char* ToString(TranslucencyDemo demo) { return demo == TranslucencyDemo::Smoke ? "smoke" : "shards"; }
const char* ToString(TranslucencyMethod method) {
  switch (method) {
    case TranslucencyMethod::Alpha: return "alpha";
    case TranslucencyMethod::Wboit: return "wboit";
    case TranslucencyMethod::Colored: return "colored";
    case TranslucencyMethod::Sorted: return "sorted";
  }
  return "?";
}
bool ParseDemo(const std::string& text, TranslucencyDemo* demo) {
  if (text == "smoke") *demo = TranslucencyDemo::Smoke;
  else if (text == "shards") *demo = TranslucencyDemo::Shards;
  else return false;
  return true;
}
bool ParseMethod(const std::string& text, TranslucencyMethod* method) {
  for (auto m : {TranslucencyMethod::Alpha, TranslucencyMethod::Wboit, TranslucencyMethod::Colored,
                 TranslucencyMethod::Sorted})
    if (text == ToString(m)) {
      *method = m;
      return true;
    }
  return false;
}

struct Translucency::Impl {
  Device* device = nullptr;
  DeviceContext* context = nullptr;
  // Targets.
  ComPtr<Texture2D> frame, depth, accum, revealage;
  ComPtr<RenderTargetView> frameRtv, accumRtv, revealageRtv;
  ComPtr<DepthStencilView> dsv;
  ComPtr<ShaderResourceView> accumSrv, revealageSrv;
  // States.
  ComPtr<BlendState> over, wboitAccum, coloredAccum, wboitCompose, coloredCompose;
  ComPtr<DepthStencilState> opaqueDepth, testNoWrite, noDepth;
  ComPtr<RasterizerState> noCull;
  ComPtr<SamplerState> linear;
  // Opaque.
  ComPtr<VertexShader> opaqueVs;
  ComPtr<PixelShader> opaquePs;
  ComPtr<InputLayout> opaqueLayout;
  ComPtr<Buffer> opaqueVb, opaqueCb;
  UINT opaqueVertices = 0;
  // Smoke.
  ComPtr<VertexShader> smokeVs;
  ComPtr<GeometryShader> smokeGs;
  ComPtr<PixelShader> smokePs[3];  // over, wboit, colored
  ComPtr<InputLayout> smokeLayout;
  ComPtr<Buffer> smokeCb, particleStaging, sortedParticles;
  ComPtr<ShaderResourceView> puff;
  ComPtr<Query> soStats;
  UINT sortedCount = 0;
  // Shards.
  ComPtr<VertexShader> shardVs;
  ComPtr<PixelShader> shardPs[3];
  ComPtr<InputLayout> shardLayout;
  ComPtr<Buffer> shardVb, shardIb, instances, sortedInstances, shardCb;
  std::vector<ShardInstance> instanceData;
  UINT shardIndices = 0;
  // Compose.
  ComPtr<VertexShader> fullscreenVs;
  ComPtr<PixelShader> composePs;
  // Timing.
  ComPtr<Query> disjoint, stamps[5];
  bool timesPending = false;
  bool countThisFrame = false;  // SO_STATISTICS around this frame's update (sorted needs the count)
};

Translucency::~Translucency() = default;

std::unique_ptr<Translucency> Translucency::Create(Device* device, DeviceContext* context,
                                                   const TranslucencySettings& settings, std::string* error) {
  std::unique_ptr<Translucency> t(new Translucency());
  if (!t->Initialize(device, context, settings, error)) return nullptr;
  return t;
}

bool Translucency::Initialize(Device* device, DeviceContext* context, const TranslucencySettings& s,
                              std::string* error) {
  settings_ = s;
  impl_ = std::make_unique<Impl>();
  Impl& m = *impl_;
  m.device = device;
  m.context = context;
  auto fail = [&](const std::string& what) {
    if (error->empty()) *error = "Translucency: " + what + " failed";
    return false;
  };
  auto vs = [&](const char* file, const char* entry, ComPtr<VertexShader>* out, std::vector<uint32_t>* code) {
    return Compile(file, entry, "vs_5_0", code, error) &&
           SUCCEEDED(device->CreateVertexShader(code->data(), code->size() * 4, nullptr, out->GetAddressOf()));
  };
  auto ps = [&](const char* file, const char* entry, ComPtr<PixelShader>* out) {
    std::vector<uint32_t> code;
    return Compile(file, entry, "ps_5_0", &code, error) &&
           SUCCEEDED(device->CreatePixelShader(code.data(), code.size() * 4, nullptr, out->GetAddressOf()));
  };
  auto buffer = [&](UINT size, USAGE usage, UINT bind, UINT cpu, const void* data, ComPtr<Buffer>* out) {
    BUFFER_DESC d{size, usage, bind, cpu, 0, 0};
    SUBRESOURCE_DATA init{data, 0, 0};
    return SUCCEEDED(device->CreateBuffer(&d, data ? &init : nullptr, out->GetAddressOf()));
  };

  // Targets: the frame (R8G8B8A8_UNORM), depth, accum and revealage of Tables 1-4.
  auto texture = [&](DXGI_FORMAT format, UINT bind, ComPtr<Texture2D>* out) {
    TEXTURE2D_DESC d{s.width, s.height, 1, 1, format, {1, 0}, USAGE_DEFAULT, bind, 0, 0};
    return SUCCEEDED(device->CreateTexture2D(&d, nullptr, out->GetAddressOf()));
  };
  if (!texture(DXGI_FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE, &m.frame) ||
      !texture(DXGI_FORMAT_D32_FLOAT, BIND_DEPTH_STENCIL, &m.depth) ||
      !texture(DXGI_FORMAT_R16G16B16A16_FLOAT, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE, &m.accum) ||
      !texture(DXGI_FORMAT_R8_UNORM, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE, &m.revealage))
    return fail("creating the targets");
  if (FAILED(device->CreateRenderTargetView(m.frame.Get(), nullptr, m.frameRtv.GetAddressOf())) ||
      FAILED(device->CreateRenderTargetView(m.accum.Get(), nullptr, m.accumRtv.GetAddressOf())) ||
      FAILED(device->CreateRenderTargetView(m.revealage.Get(), nullptr, m.revealageRtv.GetAddressOf())) ||
      FAILED(device->CreateDepthStencilView(m.depth.Get(), nullptr, m.dsv.GetAddressOf())) ||
      FAILED(device->CreateShaderResourceView(m.accum.Get(), nullptr, m.accumSrv.GetAddressOf())) ||
      FAILED(device->CreateShaderResourceView(m.revealage.Get(), nullptr, m.revealageSrv.GetAddressOf())))
    return fail("creating the views");

  // States.
  BLEND_DESC over;
  over.RenderTarget[0] = oit::TargetBlend(BLEND_SRC_ALPHA, BLEND_INV_SRC_ALPHA, BLEND_ONE, BLEND_INV_SRC_ALPHA);
  const BLEND_DESC wboitAccum = oit::WboitAccumulateBlend(), coloredAccum = oit::ColoredAccumulateBlend(),
                   wboitCompose = oit::WboitComposeBlend(),
                   coloredCompose = s.literalTable4 ? oit::ColoredComposeBlendLiteral()
                                                    : oit::ColoredComposeBlendCorrected();
  if (FAILED(device->CreateBlendState(&over, m.over.GetAddressOf())) ||
      FAILED(device->CreateBlendState(&wboitAccum, m.wboitAccum.GetAddressOf())) ||
      FAILED(device->CreateBlendState(&coloredAccum, m.coloredAccum.GetAddressOf())) ||
      FAILED(device->CreateBlendState(&wboitCompose, m.wboitCompose.GetAddressOf())) ||
      FAILED(device->CreateBlendState(&coloredCompose, m.coloredCompose.GetAddressOf())))
    return fail("creating the blend states");
  DEPTH_STENCIL_DESC opaqueDepth{};  // D3D11 defaults: test LESS, write ALL
  DEPTH_STENCIL_DESC testNoWrite = opaqueDepth;
  testNoWrite.DepthWriteMask = DEPTH_WRITE_MASK_ZERO;
  DEPTH_STENCIL_DESC noDepth = opaqueDepth;
  noDepth.DepthEnable = FALSE;
  noDepth.DepthWriteMask = DEPTH_WRITE_MASK_ZERO;
  RASTERIZER_DESC noCull{};
  noCull.CullMode = CULL_NONE;
  SAMPLER_DESC linear{};
  linear.AddressU = linear.AddressV = linear.AddressW = TEXTURE_ADDRESS_CLAMP;
  if (FAILED(device->CreateDepthStencilState(&opaqueDepth, m.opaqueDepth.GetAddressOf())) ||
      FAILED(device->CreateDepthStencilState(&testNoWrite, m.testNoWrite.GetAddressOf())) ||
      FAILED(device->CreateDepthStencilState(&noDepth, m.noDepth.GetAddressOf())) ||
      FAILED(device->CreateRasterizerState(&noCull, m.noCull.GetAddressOf())) ||
      FAILED(device->CreateSamplerState(&linear, m.linear.GetAddressOf())))
    return fail("creating the depth, rasterizer and sampler states");

  // Opaque background.
  std::vector<uint32_t> code;
  if (!vs("scene_opaque.hlsl", "VSOpaque", &m.opaqueVs, &code) || !ps("scene_opaque.hlsl", "PSOpaque", &m.opaquePs))
    return fail("the opaque shaders");
  const INPUT_ELEMENT_DESC opaqueElements[] = {
      {"POSITION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
      {"NORMAL", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0},
      {"COLOR", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 24, INPUT_PER_VERTEX_DATA, 0}};
  if (FAILED(device->CreateInputLayout(opaqueElements, 3, code.data(), code.size() * 4,
                                       m.opaqueLayout.GetAddressOf())))
    return fail("the opaque input layout");
  std::vector<OpaqueVertex> scene = OpaqueScene(s.neutralBackground);
  m.opaqueVertices = UINT(scene.size());
  if (!buffer(UINT(scene.size() * sizeof(OpaqueVertex)), USAGE_IMMUTABLE, BIND_VERTEX_BUFFER, 0, scene.data(),
              &m.opaqueVb) ||
      !buffer(sizeof(OpaqueParams), USAGE_DYNAMIC, BIND_CONSTANT_BUFFER, CPU_ACCESS_WRITE, nullptr, &m.opaqueCb))
    return fail("the opaque buffers");

  // Compose.
  if (!vs("translucency_compose.hlsl", "VSFullscreen", &m.fullscreenVs, &code) ||
      !ps("translucency_compose.hlsl", "PSCompose", &m.composePs))
    return fail("the compose shaders");

  // Timing.
  QUERY_DESC disjoint{QUERY_TIMESTAMP_DISJOINT, 0}, stamp{QUERY_TIMESTAMP, 0}, so{QUERY_SO_STATISTICS, 0};
  if (FAILED(device->CreateQuery(&disjoint, m.disjoint.GetAddressOf())) ||
      FAILED(device->CreateQuery(&so, m.soStats.GetAddressOf())))
    return fail("the queries");
  for (auto& q : m.stamps)
    if (FAILED(device->CreateQuery(&stamp, q.GetAddressOf()))) return fail("the timestamp queries");

  if (s.demo == TranslucencyDemo::Smoke) {
    ParticleSettings ps_;
    ps_.rule = s.rule;
    ps_.emitterCenter = {0, 0.3f, 0.5f};
    // A negative radius mirrors the emitter ring: emitters (and so their particles, in
    // buffer order) run from the front of the ring to its back, so unsorted OVER draws
    // near smoke first and far smoke on top: the failure of the paper's Fig. 1.
    ps_.emitterRadius = -1.8f;
    ps_.spread = {0.5f, 0.2f, 0.5f};
    ps_.speedUp = 1.2f;
    ps_.acceleration = {0.35f, 0.2f, 0.0f};
    ps_.secondsPerUpdate = s.secondsPerUpdate;
    ps_.size = s.particleSize;
    particles_ = ParticleSystem::Create(device, ps_, error);
    if (!particles_) return fail("the particle system");
    if (!vs("translucency_smoke.hlsl", "VSSmoke", &m.smokeVs, &code)) return fail("the smoke VS");
    std::vector<uint32_t> gs;
    if (!Compile("translucency_smoke.hlsl", "GSSmoke", "gs_5_0", &gs, error) ||
        FAILED(device->CreateGeometryShader(gs.data(), gs.size() * 4, nullptr, m.smokeGs.GetAddressOf())) ||
        !ps("translucency_smoke.hlsl", "PSSmokeOver", &m.smokePs[0]) ||
        !ps("translucency_smoke.hlsl", "PSSmokeWboit", &m.smokePs[1]) ||
        !ps("translucency_smoke.hlsl", "PSSmokeColored", &m.smokePs[2]))
      return fail("the smoke shaders");
    const INPUT_ELEMENT_DESC elements[] = {
        {"ORIGIN", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
        {"VELOCITY", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0},
        {"SEEDAGE", 0, DXGI_FORMAT_R32G32_UINT, 0, 24, INPUT_PER_VERTEX_DATA, 0},
        {"KINDLIFE", 0, DXGI_FORMAT_R32G32_UINT, 0, 32, INPUT_PER_VERTEX_DATA, 0}};
    if (FAILED(device->CreateInputLayout(elements, 4, code.data(), code.size() * 4, m.smokeLayout.GetAddressOf())))
      return fail("the smoke input layout");
    const UINT bytes = particles_->capacity() * kParticleStride;
    if (!buffer((sizeof(SmokeParams) + 15) / 16 * 16, USAGE_DYNAMIC, BIND_CONSTANT_BUFFER, CPU_ACCESS_WRITE, nullptr,
                &m.smokeCb) ||
        !buffer(bytes, USAGE_STAGING, 0, CPU_ACCESS_READ, nullptr, &m.particleStaging) ||
        !buffer(bytes, USAGE_DEFAULT, BIND_VERTEX_BUFFER, 0, nullptr, &m.sortedParticles))
      return fail("the smoke buffers");
    constexpr UINT kPuff = 64;
    std::vector<uint8_t> texels = PuffTexels(kPuff, s.seed);
    TEXTURE2D_DESC d{kPuff, kPuff, 1, 1, DXGI_FORMAT_R8G8B8A8_UNORM, {1, 0}, USAGE_IMMUTABLE, BIND_SHADER_RESOURCE,
                     0, 0};
    SUBRESOURCE_DATA init{texels.data(), kPuff * 4, 0};
    ComPtr<Texture2D> puff;
    if (FAILED(device->CreateTexture2D(&d, &init, puff.GetAddressOf())) ||
        FAILED(device->CreateShaderResourceView(puff.Get(), nullptr, m.puff.GetAddressOf())))
      return fail("the puff texture");
  } else {
    if (!vs("shards.hlsl", "VSShard", &m.shardVs, &code) || !ps("shards.hlsl", "PSShardOver", &m.shardPs[0]) ||
        !ps("shards.hlsl", "PSShardWboit", &m.shardPs[1]) || !ps("shards.hlsl", "PSShardColored", &m.shardPs[2]))
      return fail("the shard shaders");
    const INPUT_ELEMENT_DESC elements[] = {
        {"POSITION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
        {"NORMAL", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0},
        {"WORLD", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 0, INPUT_PER_INSTANCE_DATA, 1},
        {"WORLD", 1, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 16, INPUT_PER_INSTANCE_DATA, 1},
        {"WORLD", 2, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 32, INPUT_PER_INSTANCE_DATA, 1},
        {"WORLD", 3, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 48, INPUT_PER_INSTANCE_DATA, 1},
        {"TINT", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 64, INPUT_PER_INSTANCE_DATA, 1}};
    if (FAILED(device->CreateInputLayout(elements, 7, code.data(), code.size() * 4, m.shardLayout.GetAddressOf())))
      return fail("the shard input layout");
    std::vector<ShardVertex> mesh = ShardMesh(s.seed);
    std::vector<uint16_t> indices(mesh.size());
    std::iota(indices.begin(), indices.end(), uint16_t(0));
    m.shardIndices = UINT(indices.size());
    m.instanceData = ShardInstances(s);
    const UINT instanceBytes = UINT(std::max<size_t>(1, m.instanceData.size()) * sizeof(ShardInstance));
    if (!buffer(UINT(mesh.size() * sizeof(ShardVertex)), USAGE_IMMUTABLE, BIND_VERTEX_BUFFER, 0, mesh.data(),
                &m.shardVb) ||
        !buffer(UINT(indices.size() * 2), USAGE_IMMUTABLE, BIND_INDEX_BUFFER, 0, indices.data(), &m.shardIb) ||
        !buffer(instanceBytes, USAGE_DEFAULT, BIND_VERTEX_BUFFER, 0,
                m.instanceData.empty() ? nullptr : m.instanceData.data(), &m.instances) ||
        !buffer(instanceBytes, USAGE_DEFAULT, BIND_VERTEX_BUFFER, 0, nullptr, &m.sortedInstances) ||
        !buffer(sizeof(ShardParams), USAGE_DYNAMIC, BIND_CONSTANT_BUFFER, CPU_ACCESS_WRITE, nullptr, &m.shardCb))
      return fail("the shard buffers");
  }
  return true;
}

Camera Translucency::CameraForFrame(uint32_t n) const {
  const bool smoke = settings_.demo == TranslucencyDemo::Smoke;
  const glm::vec3 target = smoke ? glm::vec3(0.3f, 1.5f, 0.5f) : glm::vec3(0, 1.9f, 0);
  const float angle = 0.3f * std::sin(n * 0.01f);
  const float radius = smoke ? 7.0f : 7.5f;
  Camera c;
  c.eye = target + glm::vec3(radius * std::sin(angle), 1.2f, -radius * std::cos(angle));
  glm::mat4 view = glm::lookAtLH(c.eye, target, glm::vec3(0, 1, 0));
  glm::mat4 proj =
      glm::perspectiveLH_ZO(glm::radians(50.0f), float(settings_.width) / float(settings_.height), 0.1f, 40.0f);
  c.viewProj = proj * view;
  return c;
}

void Translucency::Timestamp(int index) {
  if (settings_.timestamps) impl_->context->End(impl_->stamps[index].Get());
}

void Translucency::RenderFrame(TranslucencyMethod method) {
  Impl& m = *impl_;
  camera_ = cameraOverride_ ? *cameraOverride_ : CameraForFrame(frame_);
  m.countThisFrame = settings_.countParticles || method == TranslucencyMethod::Sorted;
  if (settings_.timestamps) {
    m.context->Begin(m.disjoint.Get());
    Timestamp(0);
  }
  OpaquePass();
  Timestamp(1);
  ParticleUpdatePass();
  Timestamp(2);
  TransparencyPass(method);
  Timestamp(3);
  ComposePass(method);
  Timestamp(4);
  if (settings_.timestamps) {
    m.context->End(m.disjoint.Get());
    m.timesPending = true;
  }
  ++frame_;
}

void Translucency::OpaquePass() {
  Impl& m = *impl_;
  DeviceContext* ctx = m.context;
  const float sky[4] = {0.55f, 0.65f, 0.8f, 1.0f}, grey[4] = {0.6f, 0.6f, 0.6f, 1.0f};
  ctx->ClearRenderTargetView(m.frameRtv.Get(), settings_.neutralBackground ? grey : sky);
  ctx->ClearDepthStencilView(m.dsv.Get(), CLEAR_DEPTH, 1.0f, 0);
  RenderTargetView* rtv = m.frameRtv.Get();
  ctx->OMSetRenderTargets(1, &rtv, m.dsv.Get());
  VIEWPORT viewport{0, 0, float(settings_.width), float(settings_.height), 0, 1};
  ctx->RSSetViewports(1, &viewport);
  ctx->RSSetState(m.noCull.Get());
  ctx->OMSetBlendState(nullptr, nullptr, 0xffffffff);
  ctx->OMSetDepthStencilState(m.opaqueDepth.Get(), 0);
  Upload(ctx, m.opaqueCb.Get(), OpaqueParams{camera_.viewProj, kLightDir, 0.45f});
  UINT stride = sizeof(OpaqueVertex), offset = 0;
  Buffer* vb = m.opaqueVb.Get();
  ctx->IASetInputLayout(m.opaqueLayout.Get());
  ctx->IASetVertexBuffers(0, 1, &vb, &stride, &offset);
  ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx->VSSetShader(m.opaqueVs.Get(), nullptr, 0);
  ctx->GSSetShader(nullptr, nullptr, 0);
  ctx->PSSetShader(m.opaquePs.Get(), nullptr, 0);
  Buffer* cb = m.opaqueCb.Get();
  ctx->VSSetConstantBuffers(0, 1, &cb);
  ctx->PSSetConstantBuffers(0, 1, &cb);
  ctx->Draw(m.opaqueVertices, 0);
}

void Translucency::ParticleUpdatePass() {
  if (!particles_) return;
  Impl& m = *impl_;
  const bool count = m.countThisFrame || settings_.countParticles;
  if (count) m.context->Begin(m.soStats.Get());
  particles_->Update(m.context);
  if (count) {
    m.context->End(m.soStats.Get());
    QUERY_DATA_SO_STATISTICS data{};
    while (m.context->GetData(m.soStats.Get(), &data, sizeof data, 0) == S_FALSE) {
    }
    particleCount_ = data.NumPrimitivesWritten;
  }
}

void Translucency::TransparencyPass(TranslucencyMethod method) {
  Impl& m = *impl_;
  DeviceContext* ctx = m.context;
  switch (method) {
    case TranslucencyMethod::Alpha:
    case TranslucencyMethod::Sorted: {
      RenderTargetView* rtv = m.frameRtv.Get();
      ctx->OMSetRenderTargets(1, &rtv, m.dsv.Get());
      ctx->OMSetBlendState(m.over.Get(), nullptr, 0xffffffff);
      break;
    }
    case TranslucencyMethod::Wboit:
    case TranslucencyMethod::Colored: {
      const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 0, 0, 0};
      ctx->ClearRenderTargetView(m.accumRtv.Get(), zero);
      ctx->ClearRenderTargetView(m.revealageRtv.Get(), one);
      RenderTargetView* rtvs[3] = {m.accumRtv.Get(), m.revealageRtv.Get(), m.frameRtv.Get()};
      const bool colored = method == TranslucencyMethod::Colored;
      ctx->OMSetRenderTargets(colored ? 3 : 2, rtvs, m.dsv.Get());
      ctx->OMSetBlendState(colored ? m.coloredAccum.Get() : m.wboitAccum.Get(), nullptr, 0xffffffff);
      break;
    }
  }
  ctx->OMSetDepthStencilState(m.testNoWrite.Get(), 0);  // test depth, write none
  ctx->RSSetState(m.noCull.Get());
  if (settings_.demo == TranslucencyDemo::Smoke)
    DrawSmoke(method);
  else
    DrawShards(method);
}

void Translucency::DrawSmoke(TranslucencyMethod method) {
  Impl& m = *impl_;
  DeviceContext* ctx = m.context;
  const ParticleSettings& ps = particles_->settings();
  Upload(ctx, m.smokeCb.Get(),
         SmokeParams{camera_.viewProj, camera_.eye, ps.secondsPerUpdate, ps.acceleration, ps.size, kLightDir, 0});
  Buffer* input = particles_->current();
  UINT count = 0;
  if (method == TranslucencyMethod::Sorted) {
    // The reference: read the particles back, sort them back to front by view depth, draw in that order.
    const uint64_t live = particleCount_;  // SO_STATISTICS of this frame's update (RenderFrame asks for it)
    ctx->CopyResource(m.particleStaging.Get(), input);
    MAPPED_SUBRESOURCE mapped{};
    std::vector<ParticleData> sorted;
    if (SUCCEEDED(ctx->Map(m.particleStaging.Get(), 0, MAP_READ, 0, &mapped))) {
      const auto* data = static_cast<const ParticleData*>(mapped.pData);
      const size_t n = std::min<uint64_t>(live, particles_->capacity());
      sorted.assign(data, data + n);
      ctx->Unmap(m.particleStaging.Get(), 0);
    }
    const glm::vec3 forward = glm::normalize(glm::vec3(camera_.viewProj[0][3], camera_.viewProj[1][3],
                                                       camera_.viewProj[2][3]));  // the w row: view depth
    std::vector<float> depth(sorted.size());
    for (size_t i = 0; i < sorted.size(); ++i) {
      const ParticleData& p = sorted[i];
      float t = p.seedAge[1] * ps.secondsPerUpdate;
      glm::vec3 c = 0.5f * t * t * ps.acceleration + t * glm::vec3(p.velocity[0], p.velocity[1], p.velocity[2]) +
                    glm::vec3(p.origin[0], p.origin[1], p.origin[2]);
      depth[i] = glm::dot(c - camera_.eye, forward);
    }
    std::vector<uint32_t> order(sorted.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return depth[a] > depth[b]; });
    std::vector<ParticleData> out(particles_->capacity());
    for (size_t i = 0; i < order.size(); ++i) out[i] = sorted[order[i]];
    ctx->UpdateSubresource(m.sortedParticles.Get(), 0, nullptr, out.data(), 0, 0);
    input = m.sortedParticles.Get();
    count = UINT(order.size());
  }
  UINT stride = kParticleStride, offset = 0;
  ctx->IASetInputLayout(m.smokeLayout.Get());
  ctx->IASetVertexBuffers(0, 1, &input, &stride, &offset);
  ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_POINTLIST);
  ctx->VSSetShader(m.smokeVs.Get(), nullptr, 0);
  ctx->GSSetShader(m.smokeGs.Get(), nullptr, 0);
  const int psIndex = method == TranslucencyMethod::Wboit ? 1 : method == TranslucencyMethod::Colored ? 2 : 0;
  ctx->PSSetShader(m.smokePs[psIndex].Get(), nullptr, 0);
  Buffer* cb = m.smokeCb.Get();
  ctx->VSSetConstantBuffers(1, 1, &cb);
  ctx->GSSetConstantBuffers(1, 1, &cb);
  ctx->PSSetConstantBuffers(1, 1, &cb);
  ShaderResourceView* srv = m.puff.Get();
  ctx->PSSetShaderResources(0, 1, &srv);
  SamplerState* sampler = m.linear.Get();
  ctx->PSSetSamplers(0, 1, &sampler);
  if (method == TranslucencyMethod::Sorted)
    ctx->Draw(count, 0);
  else
    ctx->DrawAuto();  // the CPU does not know how many particles survived
  ctx->GSSetShader(nullptr, nullptr, 0);
  ShaderResourceView* none = nullptr;
  ctx->PSSetShaderResources(0, 1, &none);
}

void Translucency::DrawShards(TranslucencyMethod method) {
  Impl& m = *impl_;
  DeviceContext* ctx = m.context;
  if (m.instanceData.empty()) return;
  Upload(ctx, m.shardCb.Get(),
         ShardParams{camera_.viewProj, camera_.eye, settings_.shardSurfaceTint, kLightDir, 0});
  Buffer* instances = m.instances.Get();
  if (method == TranslucencyMethod::Sorted) {
    // The reference: instances reordered back to front by the view depth of their centre.
    const glm::vec3 forward =
        glm::normalize(glm::vec3(camera_.viewProj[0][3], camera_.viewProj[1][3], camera_.viewProj[2][3]));
    std::vector<float> depth(m.instanceData.size());
    for (size_t i = 0; i < depth.size(); ++i)
      depth[i] = glm::dot(glm::vec3(m.instanceData[i].world[3]) - camera_.eye, forward);
    std::vector<uint32_t> order(depth.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return depth[a] > depth[b]; });
    std::vector<ShardInstance> sorted(order.size());
    for (size_t i = 0; i < order.size(); ++i) sorted[i] = m.instanceData[order[i]];
    ctx->UpdateSubresource(m.sortedInstances.Get(), 0, nullptr, sorted.data(), 0, 0);
    instances = m.sortedInstances.Get();
  }
  Buffer* vbs[2] = {m.shardVb.Get(), instances};
  UINT strides[2] = {sizeof(ShardVertex), sizeof(ShardInstance)}, offsets[2] = {0, 0};
  ctx->IASetInputLayout(m.shardLayout.Get());
  ctx->IASetVertexBuffers(0, 2, vbs, strides, offsets);
  ctx->IASetIndexBuffer(m.shardIb.Get(), DXGI_FORMAT_R16_UINT, 0);
  ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx->VSSetShader(m.shardVs.Get(), nullptr, 0);
  ctx->GSSetShader(nullptr, nullptr, 0);
  const int psIndex = method == TranslucencyMethod::Wboit ? 1 : method == TranslucencyMethod::Colored ? 2 : 0;
  ctx->PSSetShader(m.shardPs[psIndex].Get(), nullptr, 0);
  Buffer* cb = m.shardCb.Get();
  ctx->VSSetConstantBuffers(1, 1, &cb);
  ctx->PSSetConstantBuffers(1, 1, &cb);
  ctx->DrawIndexedInstanced(m.shardIndices, UINT(m.instanceData.size()), 0, 0, 0);
}

void Translucency::ComposePass(TranslucencyMethod method) {
  if (method != TranslucencyMethod::Wboit && method != TranslucencyMethod::Colored) return;
  Impl& m = *impl_;
  DeviceContext* ctx = m.context;
  RenderTargetView* rtv = m.frameRtv.Get();
  ctx->OMSetRenderTargets(1, &rtv, nullptr);
  ctx->OMSetBlendState(method == TranslucencyMethod::Wboit ? m.wboitCompose.Get() : m.coloredCompose.Get(), nullptr,
                       0xffffffff);
  ctx->OMSetDepthStencilState(m.noDepth.Get(), 0);
  ctx->IASetInputLayout(nullptr);
  ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx->VSSetShader(m.fullscreenVs.Get(), nullptr, 0);
  ctx->GSSetShader(nullptr, nullptr, 0);
  ctx->PSSetShader(m.composePs.Get(), nullptr, 0);
  ShaderResourceView* srvs[2] = {m.accumSrv.Get(), m.revealageSrv.Get()};
  ctx->PSSetShaderResources(0, 2, srvs);
  ctx->Draw(3, 0);
  ShaderResourceView* none[2] = {nullptr, nullptr};
  ctx->PSSetShaderResources(0, 2, none);
}

std::vector<uint8_t> Translucency::ReadFrame() {
  Impl& m = *impl_;
  TEXTURE2D_DESC desc;
  m.frame->GetDesc(&desc);
  desc.BindFlags = 0;
  desc.Usage = USAGE_STAGING;
  desc.CPUAccessFlags = CPU_ACCESS_READ;
  desc.MiscFlags = 0;
  ComPtr<Texture2D> staging;
  std::vector<uint8_t> pixels(size_t(settings_.width) * settings_.height * 4);
  if (FAILED(m.device->CreateTexture2D(&desc, nullptr, staging.GetAddressOf()))) return {};
  m.context->CopyResource(staging.Get(), m.frame.Get());
  MAPPED_SUBRESOURCE mapped{};
  if (FAILED(m.context->Map(staging.Get(), 0, MAP_READ, 0, &mapped))) return {};
  for (UINT y = 0; y < settings_.height; ++y)
    std::memcpy(&pixels[size_t(y) * settings_.width * 4], static_cast<const uint8_t*>(mapped.pData) + y * mapped.RowPitch,
                settings_.width * 4);
  m.context->Unmap(staging.Get(), 0);
  return pixels;
}

PassTimes Translucency::LastTimes() {
  Impl& m = *impl_;
  PassTimes t;
  if (!m.timesPending) return t;
  m.timesPending = false;
  QUERY_DATA_TIMESTAMP_DISJOINT disjoint{};
  while (m.context->GetData(m.disjoint.Get(), &disjoint, sizeof disjoint, 0) == S_FALSE) {
  }
  UINT64 stamps[5] = {};
  for (int i = 0; i < 5; ++i)
    while (m.context->GetData(m.stamps[i].Get(), &stamps[i], sizeof stamps[i], 0) == S_FALSE) {
    }
  if (disjoint.Disjoint || disjoint.Frequency == 0) return t;
  auto ms = [&](int a, int b) { return double(stamps[b] - stamps[a]) * 1000.0 / double(disjoint.Frequency); };
  t.valid = true;
  t.opaqueMs = ms(0, 1);
  t.updateMs = ms(1, 2);
  t.transparencyMs = ms(2, 3);
  t.composeMs = ms(3, 4);
  t.totalMs = ms(0, 4);
  return t;
}

double Rmse(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  if (a.size() != b.size() || a.empty()) return std::numeric_limits<double>::infinity();
  double sum = 0;
  size_t n = 0;
  for (size_t i = 0; i < a.size(); i += 4)
    for (int c = 0; c < 3; ++c, ++n) {
      double d = double(a[i + c]) - double(b[i + c]);
      sum += d * d;
    }
  return std::sqrt(sum / double(n));
}

double Psnr(double rmse) {
  return rmse == 0 ? std::numeric_limits<double>::infinity() : 20.0 * std::log10(255.0 / rmse);
}

}  // namespace renderer
