#include "renderer/translucency.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "fx/effect.h"
#include "rhi/capture.h"
#include "rhi/query_wait.h"

namespace renderer {

using namespace rhi;

namespace {

const std::string kShaderDir = PROJECT_SOURCE_ROOT "/shaders_hlsl";

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

// The effect variables the frame sets, looked up once (FX11's usual pattern).
struct SceneVars {
  fx::EffectMatrixVariable* viewProj = nullptr;
  fx::EffectVectorVariable* lightDir = nullptr;
  fx::EffectScalarVariable* ambient = nullptr;
};
struct SmokeVars {
  fx::EffectScalarVariable *frame = nullptr, *spawnPerFrame = nullptr, *minLife = nullptr, *lifeRange = nullptr,
                           *speedUp = nullptr, *seconds = nullptr, *size = nullptr, *flame = nullptr;
  fx::EffectVectorVariable *spread = nullptr, *eye = nullptr, *acceleration = nullptr, *lightDir = nullptr;
  fx::EffectMatrixVariable* viewProj = nullptr;
  fx::EffectShaderResourceVariable *puff = nullptr, *accum = nullptr, *revealage = nullptr;
};
struct ShardVars {
  fx::EffectMatrixVariable* viewProj = nullptr;
  fx::EffectVectorVariable *eye = nullptr, *lightDir = nullptr;
  fx::EffectScalarVariable* surfaceTint = nullptr;
  fx::EffectShaderResourceVariable *accum = nullptr, *revealage = nullptr;
};

// The passes of one translucency method in one effect: the 3D transparency pass
// and, for WBOIT and colored OIT, the 2D composing pass.
struct MethodPasses {
  fx::EffectPass* transparency = nullptr;
  fx::EffectPass* compose = nullptr;
};

void SetMatrix(fx::EffectMatrixVariable* v, const glm::mat4& m) {
  v->SetMatrixTranspose(&m[0][0]);  // GLM stores columns: the transpose of FX11's row-major array
}
void SetVector(fx::EffectVectorVariable* v, const glm::vec3& x) {
  const float f[4] = {x.x, x.y, x.z, 0};
  v->SetFloatVector(f);
}

}  // namespace

struct Translucency::Impl {
  Device* device = nullptr;
  DeviceContext* context = nullptr;
  // Effects (shaders_hlsl/scene.fx, smoke.fx, shards.fx).
  ComPtr<fx::Effect> sceneFx, smokeFx, shardsFx;
  fx::EffectPass* opaquePass = nullptr;
  fx::EffectPass* updatePass = nullptr;
  MethodPasses passes[4];  // by TranslucencyMethod: alpha (fire: additive), wboit, colored, sorted (= OVER)
  fx::EffectPass* shardPasses[4] = {};  // shards.fx <method>/Transparency
  SceneVars scene;
  SmokeVars smoke;
  ShardVars shard;
  // Targets.
  ComPtr<Texture2D> frame, depth, accum, revealage;
  ComPtr<RenderTargetView> frameRtv, accumRtv, revealageRtv;
  ComPtr<DepthStencilView> dsv;
  ComPtr<ShaderResourceView> accumSrv, revealageSrv;
  // Opaque.
  ComPtr<InputLayout> opaqueLayout;
  ComPtr<Buffer> opaqueVb;
  UINT opaqueVertices = 0;
  // Particles: the init buffer (the emitters) and the stream-output ping-pong pair.
  ParticleSettings particleSettings;
  uint32_t capacity = 0, updates = 0, current = 0;
  ComPtr<Buffer> emitters, pingPong[2];
  ComPtr<InputLayout> updateLayout, smokeLayout;
  ComPtr<Buffer> particleStaging, sortedParticles;
  ComPtr<ShaderResourceView> puff;
  ComPtr<Query> soStats;
  // Shards.
  ComPtr<InputLayout> shardLayout;
  ComPtr<Buffer> shardVb, shardIb, instances, sortedInstances;
  UINT shardIndices = 0;
  std::vector<ShardInstance> instanceData;
  // Timing.
  ComPtr<Query> disjoint, stamps[5], transparencyStatistics;
  bool timesPending = false;
  bool countThisFrame = false;

  bool particlesOn() const { return capacity > 0; }
};

std::unique_ptr<Translucency> Translucency::Create(Device* device, DeviceContext* context,
                                                   const TranslucencySettings& settings, std::string* error) {
  std::unique_ptr<Translucency> t(new Translucency());
  std::string local;
  if (!error) error = &local;
  if (!t->Initialize(device, context, settings, error)) return nullptr;
  return t;
}

Translucency::~Translucency() = default;

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
  auto buffer = [&](UINT size, USAGE usage, UINT bind, UINT cpu, const void* data, ComPtr<Buffer>* out) {
    BUFFER_DESC d{size, usage, bind, cpu, 0, 0};
    SUBRESOURCE_DATA init{data, 0, 0};
    return SUCCEEDED(device->CreateBuffer(&d, data ? &init : nullptr, out->GetAddressOf()));
  };
  auto load = [&](const char* file, ComPtr<fx::Effect>* out,
                  std::vector<std::pair<std::string, std::string>> defines = {}) {
    fx::EFFECT_OPTIONS options;
    options.IncludeDirs = {kShaderDir};
    options.Defines = std::move(defines);
    std::string errors;
    options.Errors = &errors;
    if (FAILED(fx::CreateEffectFromFile((kShaderDir + "/" + file).c_str(), options, device, out->GetAddressOf()))) {
      *error = std::string(file) + ": " + errors;
      return false;
    }
    return true;
  };
  auto pass = [&](fx::Effect* e, const char* technique, const char* name) -> fx::EffectPass* {
    fx::EffectPass* p = e->GetTechniqueByName(technique)->GetPassByName(name);
    if (!p->IsValid()) {
      if (error->empty()) *error = std::string("Translucency: no pass ") + technique + "/" + name;
      return nullptr;
    }
    return p;
  };
  auto layout = [&](fx::EffectPass* p, const INPUT_ELEMENT_DESC* elements, UINT n, ComPtr<InputLayout>* out) {
    fx::PASS_DESC desc;
    return p && SUCCEEDED(p->GetDesc(&desc)) &&
           SUCCEEDED(device->CreateInputLayout(elements, n, desc.pIAInputSignature, desc.IAInputSignatureSize,
                                               out->GetAddressOf()));
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

  // Opaque background: scene.fx, technique Opaque.
  if (!load("scene.fx", &m.sceneFx)) return fail("scene.fx");
  m.opaquePass = pass(m.sceneFx.Get(), "Opaque", "Scene");
  const INPUT_ELEMENT_DESC opaqueElements[] = {
      {"POSITION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
      {"NORMAL", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0},
      {"COLOR", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 24, INPUT_PER_VERTEX_DATA, 0}};
  if (!layout(m.opaquePass, opaqueElements, 3, &m.opaqueLayout)) return fail("the opaque input layout");
  m.scene.viewProj = m.sceneFx->GetVariableByName("ViewProj")->AsMatrix();
  m.scene.lightDir = m.sceneFx->GetVariableByName("LightDir")->AsVector();
  m.scene.ambient = m.sceneFx->GetVariableByName("Ambient")->AsScalar();
  std::vector<OpaqueVertex> scene = OpaqueScene(s.neutralBackground);
  m.opaqueVertices = UINT(scene.size());
  if (!buffer(UINT(scene.size() * sizeof(OpaqueVertex)), USAGE_IMMUTABLE, BIND_VERTEX_BUFFER, 0, scene.data(),
              &m.opaqueVb))
    return fail("the opaque buffers");

  // Timing.
  QUERY_DESC disjoint{QUERY_TIMESTAMP_DISJOINT, 0}, stamp{QUERY_TIMESTAMP, 0}, so{QUERY_SO_STATISTICS, 0},
      statistics{QUERY_PIPELINE_STATISTICS, 0};
  if (FAILED(device->CreateQuery(&disjoint, m.disjoint.GetAddressOf())) ||
      FAILED(device->CreateQuery(&so, m.soStats.GetAddressOf())) ||
      FAILED(device->CreateQuery(&statistics, m.transparencyStatistics.GetAddressOf())))
    return fail("the queries");
  for (auto& q : m.stamps)
    if (FAILED(device->CreateQuery(&stamp, q.GetAddressOf()))) return fail("the timestamp queries");

  const bool fire = s.demo == TranslucencyDemo::Fire;
  if (s.demo == TranslucencyDemo::Smoke || fire) {
    ParticleSettings& ps_ = m.particleSettings;
    ps_.rule = s.rule;
    if (fire) {
      // Flames: a tight ring of emitters near the floor, fast buoyant rise, short lives.
      ps_.emitterCenter = {0, 0.2f, 0.5f};
      ps_.emitterRadius = -0.45f;
      ps_.spread = {0.3f, 0.25f, 0.3f};
      ps_.speedUp = 0.9f;
      ps_.acceleration = {0.1f, 1.2f, 0.0f};
    } else {
      ps_.emitterCenter = {0, 0.3f, 0.5f};
      // A negative radius mirrors the emitter ring: emitters (and so their particles, in
      // buffer order) run from the front of the ring to its back, so unsorted OVER draws
      // near smoke first and far smoke on top: the failure of the paper's Fig. 1.
      ps_.emitterRadius = -1.8f;
      ps_.spread = {0.5f, 0.2f, 0.5f};
      ps_.speedUp = 1.2f;
      ps_.acceleration = {0.35f, 0.2f, 0.0f};
    }
    ps_.secondsPerUpdate = s.secondsPerUpdate;
    ps_.size = s.particleSize;
    const ParticleRule& rule = s.rule;
    if (rule.spawnPerFrame > 16 || rule.lifeRange == 0 || rule.emitters == 0)
      return fail("the particle rule (spawnPerFrame <= 16, lifeRange > 0, emitters > 0)");
    // The most particles the rule can keep alive: every emitter with a full set of
    // children of the longest lifetime.
    const uint64_t most =
        uint64_t(rule.emitters) * (1 + uint64_t(rule.spawnPerFrame) * (rule.minLife + rule.lifeRange));
    if (most * kParticleStride > (uint64_t(1) << 31)) return fail("the particle buffers (more than 2 GiB)");
    m.capacity = uint32_t(most);

    if (!load("smoke.fx", &m.smokeFx, {MaxSpawnPerUpdateDefine(rule)})) return fail("smoke.fx");
    fx::Effect* e = m.smokeFx.Get();
    m.updatePass = pass(e, "Update", "StreamOut");
    m.passes[int(TranslucencyMethod::Alpha)] = {pass(e, fire ? "Fire" : "Alpha", "Transparency"), nullptr};
    m.passes[int(TranslucencyMethod::Sorted)] = m.passes[int(TranslucencyMethod::Alpha)];
    m.passes[int(TranslucencyMethod::Wboit)] = {pass(e, "Wboit", "Transparency"), pass(e, "Wboit", "Compose")};
    const char* colored = s.literalTable4 ? "ColoredLiteral" : "Colored";
    m.passes[int(TranslucencyMethod::Colored)] = {pass(e, colored, "Transparency"), pass(e, colored, "Compose")};
    for (const MethodPasses& p : m.passes)
      if (!p.transparency) return fail("the smoke passes");
    if (!m.updatePass || !m.passes[1].compose || !m.passes[2].compose) return fail("the smoke passes");
    const INPUT_ELEMENT_DESC elements[] = {
        {"ORIGIN", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
        {"VELOCITY", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0},
        {"SEEDAGE", 0, DXGI_FORMAT_R32G32_UINT, 0, 24, INPUT_PER_VERTEX_DATA, 0},
        {"KINDLIFE", 0, DXGI_FORMAT_R32G32_UINT, 0, 32, INPUT_PER_VERTEX_DATA, 0}};
    if (!layout(m.updatePass, elements, 4, &m.updateLayout) ||
        !layout(m.passes[0].transparency, elements, 4, &m.smokeLayout))
      return fail("the particle input layouts");
    SmokeVars& v = m.smoke;
    v.frame = e->GetVariableByName("Frame")->AsScalar();
    v.spawnPerFrame = e->GetVariableByName("SpawnPerFrame")->AsScalar();
    v.minLife = e->GetVariableByName("MinLife")->AsScalar();
    v.lifeRange = e->GetVariableByName("LifeRange")->AsScalar();
    v.spread = e->GetVariableByName("Spread")->AsVector();
    v.speedUp = e->GetVariableByName("SpeedUp")->AsScalar();
    v.viewProj = e->GetVariableByName("ViewProj")->AsMatrix();
    v.eye = e->GetVariableByName("Eye")->AsVector();
    v.seconds = e->GetVariableByName("Seconds")->AsScalar();
    v.acceleration = e->GetVariableByName("Acceleration")->AsVector();
    v.size = e->GetVariableByName("Size")->AsScalar();
    v.lightDir = e->GetVariableByName("LightDir")->AsVector();
    v.flame = e->GetVariableByName("Flame")->AsScalar();
    v.puff = e->GetVariableByName("Puff")->AsShaderResource();
    v.accum = e->GetVariableByName("Accum")->AsShaderResource();
    v.revealage = e->GetVariableByName("Revealage")->AsShaderResource();
    // Constant for the whole replay.
    v.spawnPerFrame->SetInt(int(rule.spawnPerFrame));
    v.minLife->SetInt(int(rule.minLife));
    v.lifeRange->SetInt(int(rule.lifeRange));
    SetVector(v.spread, ps_.spread);
    v.speedUp->SetFloat(ps_.speedUp);
    v.seconds->SetFloat(ps_.secondsPerUpdate);
    SetVector(v.acceleration, ps_.acceleration);
    v.size->SetFloat(ps_.size);
    SetVector(v.lightDir, kLightDir);
    v.flame->SetFloat(fire ? 1.0f : 0.0f);

    // The init buffer: the emitters, spread on a circle, drawn with Draw(emitters, 0) by the
    // first update (the paper's one-emitter init buffer is the case emitters == 1).
    std::vector<ParticleData> emitters(rule.emitters);
    for (uint32_t i = 0; i < rule.emitters; ++i) {
      float angle = 6.2831853f * i / rule.emitters;
      emitters[i] = {{ps_.emitterCenter.x + ps_.emitterRadius * std::cos(angle), ps_.emitterCenter.y,
                      ps_.emitterCenter.z + ps_.emitterRadius * std::sin(angle)},
                     {0, 0, 0},
                     {i, 0},
                     {0, 0}};
    }
    const UINT bytes = m.capacity * kParticleStride;
    if (!buffer(UINT(emitters.size() * kParticleStride), USAGE_IMMUTABLE, BIND_VERTEX_BUFFER, 0, emitters.data(),
                &m.emitters) ||
        !buffer(bytes, USAGE_DEFAULT, BIND_VERTEX_BUFFER | BIND_STREAM_OUTPUT, 0, nullptr, &m.pingPong[0]) ||
        !buffer(bytes, USAGE_DEFAULT, BIND_VERTEX_BUFFER | BIND_STREAM_OUTPUT, 0, nullptr, &m.pingPong[1]) ||
        !buffer(bytes, USAGE_STAGING, 0, CPU_ACCESS_READ, nullptr, &m.particleStaging) ||
        !buffer(bytes, USAGE_DEFAULT, BIND_VERTEX_BUFFER, 0, nullptr, &m.sortedParticles))
      return fail("the particle buffers");
    constexpr UINT kPuff = 64;
    std::vector<uint8_t> texels = PuffTexels(kPuff, s.seed);
    TEXTURE2D_DESC d{kPuff, kPuff, 1, 1, DXGI_FORMAT_R8G8B8A8_UNORM, {1, 0}, USAGE_IMMUTABLE, BIND_SHADER_RESOURCE,
                     0, 0};
    SUBRESOURCE_DATA init{texels.data(), kPuff * 4, 0};
    ComPtr<Texture2D> puff;
    if (FAILED(device->CreateTexture2D(&d, &init, puff.GetAddressOf())) ||
        FAILED(device->CreateShaderResourceView(puff.Get(), nullptr, m.puff.GetAddressOf())))
      return fail("the puff texture");
    v.puff->SetResource(m.puff.Get());
    v.accum->SetResource(m.accumSrv.Get());
    v.revealage->SetResource(m.revealageSrv.Get());
  }
  if (s.demo == TranslucencyDemo::Shards || s.extraShards > 0) {
    if (!load("shards.fx", &m.shardsFx)) return fail("shards.fx");
    fx::Effect* e = m.shardsFx.Get();
    if (s.demo == TranslucencyDemo::Shards) {
      m.passes[int(TranslucencyMethod::Alpha)] = {pass(e, "Alpha", "Transparency"), nullptr};
      m.passes[int(TranslucencyMethod::Sorted)] = m.passes[int(TranslucencyMethod::Alpha)];
      m.passes[int(TranslucencyMethod::Wboit)] = {pass(e, "Wboit", "Transparency"), pass(e, "Wboit", "Compose")};
      const char* colored = s.literalTable4 ? "ColoredLiteral" : "Colored";
      m.passes[int(TranslucencyMethod::Colored)] = {pass(e, colored, "Transparency"), pass(e, colored, "Compose")};
      for (const MethodPasses& p : m.passes)
        if (!p.transparency) return fail("the shard passes");
      if (!m.passes[1].compose || !m.passes[2].compose) return fail("the shard passes");
    }
    m.shardPasses[int(TranslucencyMethod::Alpha)] = pass(e, "Alpha", "Transparency");
    m.shardPasses[int(TranslucencyMethod::Sorted)] = m.shardPasses[int(TranslucencyMethod::Alpha)];
    m.shardPasses[int(TranslucencyMethod::Wboit)] = pass(e, "Wboit", "Transparency");
    m.shardPasses[int(TranslucencyMethod::Colored)] = pass(e, "Colored", "Transparency");
    const INPUT_ELEMENT_DESC elements[] = {
        {"POSITION", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
        {"NORMAL", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0},
        {"WORLD", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 0, INPUT_PER_INSTANCE_DATA, 1},
        {"WORLD", 1, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 16, INPUT_PER_INSTANCE_DATA, 1},
        {"WORLD", 2, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 32, INPUT_PER_INSTANCE_DATA, 1},
        {"WORLD", 3, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 48, INPUT_PER_INSTANCE_DATA, 1},
        {"TINT", 0, DXGI_FORMAT_R32G32B32A32_FLOAT, 1, 64, INPUT_PER_INSTANCE_DATA, 1}};
    if (!layout(m.shardPasses[0], elements, 7, &m.shardLayout)) return fail("the shard input layout");
    ShardVars& v = m.shard;
    v.viewProj = e->GetVariableByName("ViewProj")->AsMatrix();
    v.eye = e->GetVariableByName("Eye")->AsVector();
    v.lightDir = e->GetVariableByName("LightDir")->AsVector();
    v.surfaceTint = e->GetVariableByName("SurfaceTint")->AsScalar();
    v.accum = e->GetVariableByName("Accum")->AsShaderResource();
    v.revealage = e->GetVariableByName("Revealage")->AsShaderResource();
    SetVector(v.lightDir, kLightDir);
    v.surfaceTint->SetFloat(s.shardSurfaceTint);
    v.accum->SetResource(m.accumSrv.Get());
    v.revealage->SetResource(m.revealageSrv.Get());
    std::vector<ShardVertex> mesh = ShardMesh(s.seed);
    std::vector<uint16_t> indices(mesh.size());
    std::iota(indices.begin(), indices.end(), uint16_t(0));
    m.shardIndices = UINT(indices.size());
    TranslucencySettings instanceSettings = s;
    if (s.demo != TranslucencyDemo::Shards) instanceSettings.shardCount = s.extraShards;
    m.instanceData = ShardInstances(instanceSettings);
    const UINT instanceBytes = UINT(std::max<size_t>(1, m.instanceData.size()) * sizeof(ShardInstance));
    if (!buffer(UINT(mesh.size() * sizeof(ShardVertex)), USAGE_IMMUTABLE, BIND_VERTEX_BUFFER, 0, mesh.data(),
                &m.shardVb) ||
        !buffer(UINT(indices.size() * 2), USAGE_IMMUTABLE, BIND_INDEX_BUFFER, 0, indices.data(), &m.shardIb) ||
        !buffer(instanceBytes, USAGE_DEFAULT, BIND_VERTEX_BUFFER, 0,
                m.instanceData.empty() ? nullptr : m.instanceData.data(), &m.instances) ||
        !buffer(instanceBytes, USAGE_DEFAULT, BIND_VERTEX_BUFFER, 0, nullptr, &m.sortedInstances))
      return fail("the shard buffers");
  }
  return true;
}


const char* ToString(TranslucencyDemo demo) {
  switch (demo) {
    case TranslucencyDemo::Smoke: return "smoke";
    case TranslucencyDemo::Fire: return "fire";
    case TranslucencyDemo::Shards: return "shards";
  }
  return "?";
}
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
  else if (text == "fire") *demo = TranslucencyDemo::Fire;
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

Camera Translucency::CameraForFrame(uint32_t n) const {
  const bool shards = settings_.demo == TranslucencyDemo::Shards;
  const glm::vec3 target = shards ? glm::vec3(0, 1.9f, 0) : glm::vec3(0.3f, 1.5f, 0.5f);
  const float angle = 0.3f * std::sin(n * 0.01f);
  const float radius = shards ? 7.5f : 7.0f;
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
  if (settings_.timestamps) m.context->Begin(m.transparencyStatistics.Get());
  TransparencyPass(method);
  if (settings_.timestamps) m.context->End(m.transparencyStatistics.Get());
  Timestamp(3);
  ComposePass(method);
  Timestamp(4);
  if (settings_.timestamps) {
    m.context->End(m.disjoint.Get());
    m.timesPending = true;
  }
  ++frame_;
}

// Opaque objects: scene.fx Opaque/Scene into the frame and the depth buffer.
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
  SetMatrix(m.scene.viewProj, camera_.viewProj);
  SetVector(m.scene.lightDir, kLightDir);
  m.scene.ambient->SetFloat(0.45f);
  UINT stride = sizeof(OpaqueVertex), offset = 0;
  Buffer* vb = m.opaqueVb.Get();
  ctx->IASetInputLayout(m.opaqueLayout.Get());
  ctx->IASetVertexBuffers(0, 1, &vb, &stride, &offset);
  ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  m.opaquePass->Apply(0, ctx);
  ctx->Draw(m.opaqueVertices, 0);
}

// The particle update pass: smoke.fx Update/StreamOut, the current buffer in, the
// other ping-pong buffer out through stream output; the first update draws the
// init buffer with Draw(emitters, 0), later ones what the last update wrote (DrawAuto).
void Translucency::ParticleUpdatePass() {
  Impl& m = *impl_;
  if (!m.particlesOn()) return;
  DeviceContext* ctx = m.context;
  const bool count = m.countThisFrame || settings_.countParticles;
  if (count) ctx->Begin(m.soStats.Get());
  ++m.updates;
  m.smoke.frame->SetInt(int(m.updates));
  const bool first = m.updates == 1;
  const uint32_t target = first ? 0 : 1 - m.current;
  Buffer* input = first ? m.emitters.Get() : m.pingPong[m.current].Get();
  UINT stride = kParticleStride, offset = 0;
  ctx->IASetInputLayout(m.updateLayout.Get());
  ctx->IASetVertexBuffers(0, 1, &input, &stride, &offset);
  ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_POINTLIST);
  Buffer* out = m.pingPong[target].Get();
  ctx->SOSetTargets(1, &out, &offset);
  m.updatePass->Apply(0, ctx);
  if (first)
    ctx->Draw(settings_.rule.emitters, 0);
  else
    ctx->DrawAuto();  // the CPU does not know how many particles survived
  ctx->SOSetTargets(0, nullptr, nullptr);
  m.current = target;
  if (count) {
    ctx->End(m.soStats.Get());
    QUERY_DATA_SO_STATISTICS data{};
    if (SUCCEEDED(WaitForData(ctx, m.soStats.Get(), &data))) particleCount_ = data.NumPrimitivesWritten;
  }
}

// The 3D transparency pass of the method: its targets (cleared as Tables 1/3 say),
// then the particles (DrawAuto) and/or the shards (DrawIndexedInstanced).
void Translucency::TransparencyPass(TranslucencyMethod method) {
  Impl& m = *impl_;
  DeviceContext* ctx = m.context;
  switch (method) {
    case TranslucencyMethod::Alpha:
    case TranslucencyMethod::Sorted: {
      RenderTargetView* rtv = m.frameRtv.Get();
      ctx->OMSetRenderTargets(1, &rtv, m.dsv.Get());
      break;
    }
    case TranslucencyMethod::Wboit:
    case TranslucencyMethod::Colored: {
      const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 0, 0, 0};
      ctx->ClearRenderTargetView(m.accumRtv.Get(), zero);
      ctx->ClearRenderTargetView(m.revealageRtv.Get(), one);
      RenderTargetView* rtvs[3] = {m.accumRtv.Get(), m.revealageRtv.Get(), m.frameRtv.Get()};
      ctx->OMSetRenderTargets(method == TranslucencyMethod::Colored ? 3 : 2, rtvs, m.dsv.Get());
      break;
    }
  }
  if (m.particlesOn()) DrawSmoke(method);
  if (m.shardLayout) DrawShards(method);
}

void Translucency::DrawSmoke(TranslucencyMethod method) {
  Impl& m = *impl_;
  DeviceContext* ctx = m.context;
  const ParticleSettings& ps = m.particleSettings;
  SetMatrix(m.smoke.viewProj, camera_.viewProj);
  SetVector(m.smoke.eye, camera_.eye);
  Buffer* input = m.pingPong[m.current].Get();
  UINT count = 0;
  if (method == TranslucencyMethod::Sorted) {
    // The reference: read the particles back, sort them back to front by view depth, draw in that order.
    const uint64_t live = particleCount_;  // SO_STATISTICS of this frame's update (RenderFrame asks for it)
    ctx->CopyResource(m.particleStaging.Get(), input);
    MAPPED_SUBRESOURCE mapped{};
    std::vector<ParticleData> sorted;
    if (SUCCEEDED(ctx->Map(m.particleStaging.Get(), 0, MAP_READ, 0, &mapped))) {
      const auto* data = static_cast<const ParticleData*>(mapped.pData);
      const size_t n = std::min<uint64_t>(live, m.capacity);
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
    std::vector<ParticleData> out(m.capacity);
    for (size_t i = 0; i < order.size(); ++i) out[i] = sorted[order[i]];
    ctx->UpdateSubresource(m.sortedParticles.Get(), 0, nullptr, out.data(), 0, 0);
    input = m.sortedParticles.Get();
    count = UINT(order.size());
  }
  UINT stride = kParticleStride, offset = 0;
  ctx->IASetInputLayout(m.smokeLayout.Get());
  ctx->IASetVertexBuffers(0, 1, &input, &stride, &offset);
  ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_POINTLIST);
  m.passes[int(method)].transparency->Apply(0, ctx);
  if (method == TranslucencyMethod::Sorted)
    ctx->Draw(count, 0);
  else
    ctx->DrawAuto();  // the CPU does not know how many particles survived
}

void Translucency::DrawShards(TranslucencyMethod method) {
  Impl& m = *impl_;
  DeviceContext* ctx = m.context;
  if (m.instanceData.empty()) return;
  SetMatrix(m.shard.viewProj, camera_.viewProj);
  SetVector(m.shard.eye, camera_.eye);
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
  m.shardPasses[int(method)]->Apply(0, ctx);
  ctx->DrawIndexedInstanced(m.shardIndices, UINT(m.instanceData.size()), 0, 0, 0);
}

// The 2D composing pass (WBOIT: Table 2; colored: Table 4): a full-screen triangle
// over the frame reading accum and revealage (the effect's Accum / Revealage).
void Translucency::ComposePass(TranslucencyMethod method) {
  if (method != TranslucencyMethod::Wboit && method != TranslucencyMethod::Colored) return;
  Impl& m = *impl_;
  DeviceContext* ctx = m.context;
  RenderTargetView* rtv = m.frameRtv.Get();
  ctx->OMSetRenderTargets(1, &rtv, nullptr);  // unbinds accum and revealage from output
  ctx->IASetInputLayout(nullptr);
  ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  m.passes[int(method)].compose->Apply(0, ctx);
  ctx->Draw(3, 0);
}

Texture2D* Translucency::FrameTexture() const { return impl_->frame.Get(); }

std::vector<uint8_t> Translucency::ReadFrame() {
  std::vector<uint8_t> pixels;
  if (FAILED(rhi::CaptureTexture2D(impl_->device, impl_->context, impl_->frame.Get(), 0, &pixels))) return {};
  return pixels;
}

PassTimes Translucency::LastTimes() {
  Impl& m = *impl_;
  PassTimes t;
  if (!m.timesPending) return t;
  m.timesPending = false;
  QUERY_DATA_TIMESTAMP_DISJOINT disjoint{};
  UINT64 stamps[5] = {};
  QUERY_DATA_PIPELINE_STATISTICS statistics{};
  bool ready = SUCCEEDED(WaitForData(m.context, m.disjoint.Get(), &disjoint));
  for (int i = 0; i < 5; ++i) ready = SUCCEEDED(WaitForData(m.context, m.stamps[i].Get(), &stamps[i])) && ready;
  ready = SUCCEEDED(WaitForData(m.context, m.transparencyStatistics.Get(), &statistics)) && ready;
  if (!ready || disjoint.Disjoint || disjoint.Frequency == 0) return t;
  auto ms = [&](int a, int b) { return double(stamps[b] - stamps[a]) * 1000.0 / double(disjoint.Frequency); };
  t.valid = true;
  t.opaqueMs = ms(0, 1);
  t.updateMs = ms(1, 2);
  t.transparencyMs = ms(2, 3);
  t.composeMs = ms(3, 4);
  t.totalMs = ms(0, 4);
  t.transparencyFragments = statistics.PSInvocations;
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
