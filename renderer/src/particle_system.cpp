#include "renderer/particle_system.h"

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "hlsl/hlsl_compiler.h"

namespace renderer {

namespace {

using namespace rhi;

const std::string kShaderDir = PROJECT_SOURCE_ROOT "/shaders_hlsl";

struct Particle {
  float origin[3];
  float velocity[3];
  uint32_t seedAge[2];
  uint32_t kindLife[2];
};
static_assert(sizeof(Particle) == kParticleStride);

struct UpdateParams {
  uint32_t frame, spawnPerFrame, minLife, lifeRange;
  float spread[3];
  float speedUp;
};

struct DrawParams {
  float viewProj[16];
  float eye[3];
  float seconds;
  float acceleration[3];
  float size;
};

bool Compile(const char* file, const char* entry, const char* profile, std::vector<uint32_t>* spirv,
             std::string* error, const std::vector<hlsl::Define>& defines = {}) {
  hlsl::CompileResult result = hlsl::CompileHlslFile(kShaderDir + "/" + file, entry, profile, {kShaderDir}, defines);
  if (!result.ok) {
    *error = result.FormatErrors();
    return false;
  }
  *spirv = std::move(result.spirv);
  return true;
}

// A soft round puff: alpha falls off with the distance from the centre.
std::vector<uint8_t> PuffTexels(UINT size) {
  std::vector<uint8_t> texels(size * size * 4);
  for (UINT y = 0; y < size; ++y) {
    for (UINT x = 0; x < size; ++x) {
      float dx = (x + 0.5f) / size * 2 - 1, dy = (y + 0.5f) / size * 2 - 1;
      float falloff = std::max(0.0f, 1.0f - std::sqrt(dx * dx + dy * dy));
      uint8_t* t = &texels[(y * size + x) * 4];
      t[0] = t[1] = t[2] = static_cast<uint8_t>(200 + 55 * falloff);
      t[3] = static_cast<uint8_t>(255 * falloff * falloff);
    }
  }
  return texels;
}

}  // namespace

std::unique_ptr<ParticleSystem> ParticleSystem::Create(Device* device, const ParticleSettings& settings,
                                                       std::string* error) {
  std::unique_ptr<ParticleSystem> system(new ParticleSystem());
  if (!system->Initialize(device, settings, error)) return nullptr;
  return system;
}

bool ParticleSystem::Initialize(Device* device, const ParticleSettings& settings, std::string* error) {
  settings_ = settings;
  const ParticleRule& rule = settings.rule;
  if (rule.spawnPerFrame > 16 || rule.lifeRange == 0) {
    *error = "ParticleRule: spawnPerFrame must be at most 16 and lifeRange non-zero";
    return false;
  }
  // The most particles the rule can keep alive: every emitter with a full set
  // of children of the longest lifetime.
  const uint64_t most = uint64_t(rule.emitters) * (1 + uint64_t(rule.spawnPerFrame) * (rule.minLife + rule.lifeRange));
  capacity_ = settings.capacity ? settings.capacity : static_cast<uint32_t>(most);

  std::vector<uint32_t> passCode, updateCode, particleCode, billboardCode, smokeCode;
  constexpr const char* kUpdate = "particles_update.hlsl";
  constexpr const char* kDraw = "particles_draw.hlsl";
  const std::vector<hlsl::Define> maxSpawn = {{kMaxSpawnPerUpdateMacro, std::to_string(rule.spawnPerFrame)}};
  if (!Compile(kUpdate, "VSPassThrough", "vs_5_0", &passCode, error) ||
      !Compile(kUpdate, "GSUpdate", "gs_5_0", &updateCode, error, maxSpawn) ||
      !Compile(kDraw, "VSParticle", "vs_5_0", &particleCode, error) ||
      !Compile(kDraw, "GSBillboard", "gs_5_0", &billboardCode, error) ||
      !Compile(kDraw, "PSSmoke", "ps_5_0", &smokeCode, error))
    return false;
  auto fail = [&](const char* what) {
    *error = std::string("ParticleSystem: ") + what + " failed";
    return false;
  };
  if (FAILED(device->CreateVertexShader(passCode.data(), passCode.size() * 4, nullptr, passThrough_.GetAddressOf())) ||
      FAILED(device->CreateVertexShader(particleCode.data(), particleCode.size() * 4, nullptr,
                                        particleVs_.GetAddressOf())) ||
      FAILED(device->CreateGeometryShader(billboardCode.data(), billboardCode.size() * 4, nullptr,
                                          billboard_.GetAddressOf())) ||
      FAILED(device->CreatePixelShader(smokeCode.data(), smokeCode.size() * 4, nullptr, smoke_.GetAddressOf())))
    return fail("creating the shaders");

  const SO_DECLARATION_ENTRY decl[] = {{0, "ORIGIN", 0, 0, 3, 0},
                                       {0, "VELOCITY", 0, 0, 3, 0},
                                       {0, "SEEDAGE", 0, 0, 2, 0},
                                       {0, "KINDLIFE", 0, 0, 2, 0}};
  const UINT stride = kParticleStride;
  if (FAILED(device->CreateGeometryShaderWithStreamOutput(updateCode.data(), updateCode.size() * 4, decl, 4, &stride,
                                                          1, SO_NO_RASTERIZED_STREAM, nullptr,
                                                          update_.GetAddressOf())))
    return fail("CreateGeometryShaderWithStreamOutput");
  const INPUT_ELEMENT_DESC elements[] = {
      {"ORIGIN", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
      {"VELOCITY", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0},
      {"SEEDAGE", 0, DXGI_FORMAT_R32G32_UINT, 0, 24, INPUT_PER_VERTEX_DATA, 0},
      {"KINDLIFE", 0, DXGI_FORMAT_R32G32_UINT, 0, 32, INPUT_PER_VERTEX_DATA, 0}};
  if (FAILED(device->CreateInputLayout(elements, 4, passCode.data(), passCode.size() * 4, layout_.GetAddressOf())))
    return fail("CreateInputLayout");

  // The init buffer: the emitters, spread on a circle, drawn with Draw on the first update.
  std::vector<Particle> emitters(rule.emitters);
  for (uint32_t e = 0; e < rule.emitters; ++e) {
    float angle = 6.2831853f * e / std::max(1u, rule.emitters);
    emitters[e] = {{settings.emitterCenter.x + settings.emitterRadius * std::cos(angle), settings.emitterCenter.y,
                    settings.emitterCenter.z + settings.emitterRadius * std::sin(angle)},
                   {0, 0, 0},
                   {e, 0},
                   {0, 0}};
  }
  BUFFER_DESC initDesc{static_cast<UINT>(emitters.size() * sizeof(Particle)), USAGE_IMMUTABLE, BIND_VERTEX_BUFFER,
                       0, 0, 0};
  SUBRESOURCE_DATA initData{emitters.data(), 0, 0};
  if (FAILED(device->CreateBuffer(&initDesc, &initData, emitters_.GetAddressOf()))) return fail("the emitter buffer");
  BUFFER_DESC pingPong{capacity_ * kParticleStride, USAGE_DEFAULT, BIND_VERTEX_BUFFER | BIND_STREAM_OUTPUT, 0, 0, 0};
  for (auto& buffer : buffers_)
    if (FAILED(device->CreateBuffer(&pingPong, nullptr, buffer.GetAddressOf()))) return fail("a particle buffer");
  BUFFER_DESC params{sizeof(UpdateParams), USAGE_DYNAMIC, BIND_CONSTANT_BUFFER, CPU_ACCESS_WRITE, 0, 0};
  BUFFER_DESC drawParams{(sizeof(DrawParams) + 15) / 16 * 16, USAGE_DYNAMIC, BIND_CONSTANT_BUFFER, CPU_ACCESS_WRITE,
                         0, 0};
  if (FAILED(device->CreateBuffer(&params, nullptr, updateParams_.GetAddressOf())) ||
      FAILED(device->CreateBuffer(&drawParams, nullptr, drawParams_.GetAddressOf())))
    return fail("the constant buffers");

  // The update pass rasterizes nothing: no pixel shader and depth disabled (document 000).
  DEPTH_STENCIL_DESC noDepth{};
  noDepth.DepthEnable = FALSE;
  noDepth.DepthWriteMask = DEPTH_WRITE_MASK_ZERO;
  if (FAILED(device->CreateDepthStencilState(&noDepth, noDepth_.GetAddressOf()))) return fail("the depth state");

  constexpr UINT kPuffSize = 64;
  std::vector<uint8_t> texels = PuffTexels(kPuffSize);
  TEXTURE2D_DESC puffDesc{kPuffSize, kPuffSize, 1, 1, DXGI_FORMAT_R8G8B8A8_UNORM, {1, 0}, USAGE_IMMUTABLE,
                          BIND_SHADER_RESOURCE, 0, 0};
  SUBRESOURCE_DATA puffData{texels.data(), kPuffSize * 4, 0};
  ComPtr<Texture2D> puff;
  SAMPLER_DESC linear{};
  if (FAILED(device->CreateTexture2D(&puffDesc, &puffData, puff.GetAddressOf())) ||
      FAILED(device->CreateShaderResourceView(puff.Get(), nullptr, puff_.GetAddressOf())) ||
      FAILED(device->CreateSamplerState(&linear, linear_.GetAddressOf())))
    return fail("the puff texture");
  return true;
}

void ParticleSystem::BindParticleInput(DeviceContext* context, Buffer* buffer) {
  UINT stride = kParticleStride, offset = 0;
  context->IASetInputLayout(layout_.Get());
  context->IASetVertexBuffers(0, 1, &buffer, &stride, &offset);
  context->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_POINTLIST);
}

void ParticleSystem::Update(DeviceContext* context) {
  ++updates_;
  const ParticleRule& rule = settings_.rule;
  MAPPED_SUBRESOURCE mapped;
  if (SUCCEEDED(context->Map(updateParams_.Get(), 0, MAP_WRITE_DISCARD, 0, &mapped))) {
    UpdateParams params{updates_, rule.spawnPerFrame, rule.minLife, rule.lifeRange,
                        {settings_.spread.x, settings_.spread.y, settings_.spread.z}, settings_.speedUp};
    std::memcpy(mapped.pData, &params, sizeof params);
    context->Unmap(updateParams_.Get(), 0);
  }
  const bool first = updates_ == 1;
  const uint32_t target = first ? 0 : 1 - current_;
  BindParticleInput(context, first ? emitters_.Get() : buffers_[current_].Get());
  context->VSSetShader(passThrough_.Get(), nullptr, 0);
  context->GSSetShader(update_.Get(), nullptr, 0);
  Buffer* cb = updateParams_.Get();
  context->GSSetConstantBuffers(0, 1, &cb);
  context->PSSetShader(nullptr, nullptr, 0);
  context->OMSetDepthStencilState(noDepth_.Get(), 0);
  Buffer* out = buffers_[target].Get();
  UINT offset = 0;
  context->SOSetTargets(1, &out, &offset);
  // The first frame draws the emitters; later frames draw what the last update wrote.
  if (first)
    context->Draw(settings_.rule.emitters, 0);
  else
    context->DrawAuto();
  context->SOSetTargets(0, nullptr, nullptr);
  current_ = target;
}

void ParticleSystem::Draw(DeviceContext* context, const Camera& camera) {
  MAPPED_SUBRESOURCE mapped;
  if (SUCCEEDED(context->Map(drawParams_.Get(), 0, MAP_WRITE_DISCARD, 0, &mapped))) {
    DrawParams params{};
    // HLSL cbuffers are column_major by default: GLM's column-major storage matches.
    std::memcpy(params.viewProj, &camera.viewProj[0][0], sizeof params.viewProj);
    params.eye[0] = camera.eye.x, params.eye[1] = camera.eye.y, params.eye[2] = camera.eye.z;
    params.seconds = settings_.secondsPerUpdate;
    params.acceleration[0] = settings_.acceleration.x;
    params.acceleration[1] = settings_.acceleration.y;
    params.acceleration[2] = settings_.acceleration.z;
    params.size = settings_.size;
    std::memcpy(mapped.pData, &params, sizeof params);
    context->Unmap(drawParams_.Get(), 0);
  }
  BindParticleInput(context, buffers_[current_].Get());
  context->VSSetShader(particleVs_.Get(), nullptr, 0);
  context->GSSetShader(billboard_.Get(), nullptr, 0);
  context->PSSetShader(smoke_.Get(), nullptr, 0);
  Buffer* cb = drawParams_.Get();
  context->VSSetConstantBuffers(1, 1, &cb);
  context->GSSetConstantBuffers(1, 1, &cb);
  ShaderResourceView* srv = puff_.Get();
  context->PSSetShaderResources(0, 1, &srv);
  SamplerState* sampler = linear_.Get();
  context->PSSetSamplers(0, 1, &sampler);
  context->DrawAuto();
  context->GSSetShader(nullptr, nullptr, 0);
}

}  // namespace renderer
