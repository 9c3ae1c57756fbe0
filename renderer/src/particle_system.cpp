#include "renderer/particle_system.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "renderer/effect_files.h"
#include "rhi/query_wait.h"

namespace renderer {

namespace {

using namespace rhi;

void SetVector(fx::EffectVariable* v, const glm::vec3& x) {
  const float f[4] = {x.x, x.y, x.z, 0};
  v->AsVector()->SetFloatVector(f);
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
  if (rule.spawnPerFrame > 16 || rule.lifeRange == 0 || rule.emitters == 0) {
    *error = "ParticleRule: spawnPerFrame must be at most 16, lifeRange and emitters non-zero";
    return false;
  }
  // The most particles the rule can keep alive: every emitter with a full set
  // of children of the longest lifetime.
  const uint64_t most = uint64_t(rule.emitters) * (1 + uint64_t(rule.spawnPerFrame) * (rule.minLife + rule.lifeRange));
  const uint64_t capacity = settings.capacity ? settings.capacity : most;
  if (capacity * kParticleStride > (uint64_t(1) << 31)) {
    *error = "ParticleSystem: the particle buffers would exceed 2 GiB (" + std::to_string(capacity) + " particles)";
    return false;
  }
  capacity_ = static_cast<uint32_t>(capacity);
  auto fail = [&](const char* what) {
    if (error->empty()) *error = std::string("ParticleSystem: ") + what + " failed";
    return false;
  };

  // shaders_hlsl/particles.fx: technique Update (the stream-output pass) and Alpha (the billboards).
  effect_ = LoadEffect(device, "particles.fx", {MaxSpawnPerUpdateDefine(rule)}, error);
  if (!effect_) return false;
  updatePass_ = effect_->GetTechniqueByName("Update")->GetPassByIndex(0);
  drawPass_ = effect_->GetTechniqueByName("Alpha")->GetPassByName("Transparency");
  fx::PASS_DESC update;
  if (!updatePass_->IsValid() || !drawPass_->IsValid() || FAILED(updatePass_->GetDesc(&update)))
    return fail("finding the passes Update/StreamOut and Alpha/Transparency");
  const INPUT_ELEMENT_DESC elements[] = {
      {"ORIGIN", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
      {"VELOCITY", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0},
      {"SEEDAGE", 0, DXGI_FORMAT_R32G32_UINT, 0, 24, INPUT_PER_VERTEX_DATA, 0},
      {"KINDLIFE", 0, DXGI_FORMAT_R32G32_UINT, 0, 32, INPUT_PER_VERTEX_DATA, 0}};
  if (FAILED(device->CreateInputLayout(elements, 4, update.pIAInputSignature, update.IAInputSignatureSize,
                                       layout_.GetAddressOf())))
    return fail("CreateInputLayout");

  // The init buffer: the emitters, spread on a circle, drawn with Draw on the first update.
  std::vector<ParticleRecord> emitters(rule.emitters);
  for (uint32_t e = 0; e < rule.emitters; ++e) {
    float angle = 6.2831853f * e / std::max(1u, rule.emitters);
    emitters[e] = {{settings.emitterCenter.x + settings.emitterRadius * std::cos(angle), settings.emitterCenter.y,
                    settings.emitterCenter.z + settings.emitterRadius * std::sin(angle)},
                   {0, 0, 0},
                   {e, 0},
                   {0, 0}};
  }
  BUFFER_DESC initDesc{static_cast<UINT>(emitters.size() * sizeof(ParticleRecord)), USAGE_IMMUTABLE, BIND_VERTEX_BUFFER,
                       0, 0, 0};
  SUBRESOURCE_DATA initData{emitters.data(), 0, 0};
  if (FAILED(device->CreateBuffer(&initDesc, &initData, emitters_.GetAddressOf()))) return fail("the emitter buffer");
  // Raw views too, for shaders that read particles by index (deferred shading): D3D11
  // allows raw views of stream-output and vertex buffers, not structured ones.
  BUFFER_DESC pingPong{capacity_ * kParticleStride, USAGE_DEFAULT,
                       BIND_VERTEX_BUFFER | BIND_STREAM_OUTPUT | BIND_SHADER_RESOURCE, 0,
                       RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS, 0};
  SHADER_RESOURCE_VIEW_DESC raw{};
  raw.Format = DXGI_FORMAT_R32_TYPELESS;
  raw.ViewDimension = SRV_DIMENSION_BUFFEREX;
  raw.BufferEx = {0, capacity_ * kParticleStride / 4, BUFFEREX_SRV_FLAG_RAW};
  for (size_t i = 0; i < buffers_.size(); ++i)
    if (FAILED(device->CreateBuffer(&pingPong, nullptr, buffers_[i].GetAddressOf())) ||
        FAILED(device->CreateShaderResourceView(buffers_[i].Get(), &raw, rawViews_[i].GetAddressOf())))
      return fail("a particle buffer");

  constexpr UINT kPuffSize = 64;
  std::vector<uint8_t> texels = PuffTexels(kPuffSize);
  TEXTURE2D_DESC puffDesc{kPuffSize, kPuffSize, 1, 1, DXGI_FORMAT_R8G8B8A8_UNORM, {1, 0}, USAGE_IMMUTABLE,
                          BIND_SHADER_RESOURCE, 0, 0};
  SUBRESOURCE_DATA puffData{texels.data(), kPuffSize * 4, 0};
  ComPtr<Texture2D> puff;
  ComPtr<ShaderResourceView> puffView;
  if (FAILED(device->CreateTexture2D(&puffDesc, &puffData, puff.GetAddressOf())) ||
      FAILED(device->CreateShaderResourceView(puff.Get(), nullptr, puffView.GetAddressOf())))
    return fail("the puff texture");

  // Constant for the system's life: the rule, the motion and the puff.
  fx::Effect* e = effect_.Get();
  e->GetVariableByName("SpawnPerFrame")->AsScalar()->SetInt(int(rule.spawnPerFrame));
  e->GetVariableByName("MinLife")->AsScalar()->SetInt(int(rule.minLife));
  e->GetVariableByName("LifeRange")->AsScalar()->SetInt(int(rule.lifeRange));
  SetVector(e->GetVariableByName("Spread"), settings.spread);
  e->GetVariableByName("SpeedUp")->AsScalar()->SetFloat(settings.speedUp);
  e->GetVariableByName("Seconds")->AsScalar()->SetFloat(settings.secondsPerUpdate);
  SetVector(e->GetVariableByName("Acceleration"), settings.acceleration);
  e->GetVariableByName("Size")->AsScalar()->SetFloat(settings.size);
  e->GetVariableByName("Puff")->AsShaderResource()->SetResource(puffView.Get());
  frame_ = e->GetVariableByName("Frame")->AsScalar();
  viewProj_ = e->GetVariableByName("ViewProj")->AsMatrix();
  eye_ = e->GetVariableByName("Eye");
  QUERY_DESC statistics{QUERY_SO_STATISTICS, 0};
  if (FAILED(device->CreateQuery(&statistics, streamOutStatistics_.GetAddressOf())))
    return fail("the SO_STATISTICS query");
  return true;
}

void ParticleSystem::BindParticleInput(DeviceContext* context, Buffer* buffer) {
  UINT stride = kParticleStride, offset = 0;
  context->IASetInputLayout(layout_.Get());
  context->IASetVertexBuffers(0, 1, &buffer, &stride, &offset);
  context->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_POINTLIST);
}

void ParticleSystem::Update(DeviceContext* context, bool countLive) {
  if (countLive) context->Begin(streamOutStatistics_.Get());
  ++updates_;
  frame_->SetInt(int(updates_));
  const bool first = updates_ == 1;
  const uint32_t target = first ? 0 : 1 - current_;
  BindParticleInput(context, first ? emitters_.Get() : buffers_[current_].Get());
  Buffer* out = buffers_[target].Get();
  UINT offset = 0;
  context->SOSetTargets(1, &out, &offset);
  updatePass_->Apply(0, context);
  // The first frame draws the emitters; later frames draw what the last update wrote.
  if (first)
    context->Draw(settings_.rule.emitters, 0);
  else
    context->DrawAuto();
  context->SOSetTargets(0, nullptr, nullptr);
  current_ = target;
  if (countLive) {
    context->End(streamOutStatistics_.Get());
    QUERY_DATA_SO_STATISTICS data{};
    if (SUCCEEDED(WaitForData(context, streamOutStatistics_.Get(), &data))) liveCount_ = data.NumPrimitivesWritten;
  }
}

void ParticleSystem::Draw(DeviceContext* context, const Camera& camera) {
  viewProj_->SetMatrixTranspose(&camera.viewProj[0][0]);  // GLM stores columns: FX11's row-major, transposed
  SetVector(eye_, camera.eye);
  BindParticleInput(context, buffers_[current_].Get());
  drawPass_->Apply(0, context);
  context->DrawAuto();
}

}  // namespace renderer
