// The smoke and the flames of document 000: the particles of a ParticleSystem
// (updated by particles.fx's stream-output pass, drawn with DrawAuto because
// the CPU never knows how many survived) expanded into billboards by
// shaders_hlsl/smoke.fx, built once per transparency method.
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <vector>

#include "fx/effect.h"
#include "objects/effect_object.h"
#include "random.h"
#include "renderer/effect_files.h"

namespace renderer {
namespace {

using namespace rhi;

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

class Smoke final : public EffectObject {
 public:
  Smoke(const ObjectSetup& setup, bool fire)
      : EffectObject(setup, "smoke.fx",
                     {{"ORIGIN", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
                      {"VELOCITY", 0, DXGI_FORMAT_R32G32B32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0},
                      {"SEEDAGE", 0, DXGI_FORMAT_R32G32_UINT, 0, 24, INPUT_PER_VERTEX_DATA, 0},
                      {"KINDLIFE", 0, DXGI_FORMAT_R32G32_UINT, 0, 32, INPUT_PER_VERTEX_DATA, 0}}),
        fire_(fire) {}

  bool Initialize(const ParticleSettings& settings, std::string* error) {
    particles_ = ParticleSystem::Create(setup_.device, settings, error);
    if (!particles_) return false;
    constexpr UINT kPuff = 64;
    std::vector<uint8_t> texels = PuffTexels(kPuff, setup_.seed);
    TEXTURE2D_DESC d{kPuff, kPuff, 1, 1, DXGI_FORMAT_R8G8B8A8_UNORM, {1, 0}, USAGE_IMMUTABLE, BIND_SHADER_RESOURCE,
                     0, 0};
    SUBRESOURCE_DATA init{texels.data(), kPuff * 4, 0};
    ComPtr<Texture2D> puff;
    if (FAILED(setup_.device->CreateTexture2D(&d, &init, puff.GetAddressOf())) ||
        FAILED(setup_.device->CreateShaderResourceView(puff.Get(), nullptr, puff_.GetAddressOf()))) {
      *error = "smoke: creating the puff texture failed";
      return false;
    }
    return true;
  }

  void Update(DeviceContext* context, bool countLive) override { particles_->Update(context, countLive); }
  uint64_t LiveCount() const override { return particles_->liveCount(); }
  uint32_t QuadCapacity() const override { return particles_->capacity(); }  // smoke.fx: OBJECT_QUADS

  bool Draw(DeviceContext* ctx, const oit::MethodInfo& method, const Camera& camera, const char* pass,
            oit::DrawOrder order, std::string* error) override {
    fx::EffectPass* p = PassForFrame(method, camera, pass, error);
    if (!p) return false;
    Buffer* input = particles_->current();
    UINT sortedCount = 0;
    if (order == oit::DrawOrder::BackToFront) input = SortBackToFront(ctx, camera, &sortedCount);
    UINT stride = kParticleStride, offset = 0;
    ctx->IASetInputLayout(layout_.Get());
    ctx->IASetVertexBuffers(0, 1, &input, &stride, &offset);
    ctx->IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_POINTLIST);
    p->Apply(0, ctx);
    if (order == oit::DrawOrder::BackToFront)
      ctx->Draw(sortedCount, 0);
    else
      ctx->DrawAuto();  // the CPU does not know how many particles survived
    return true;
  }


 private:
  EffectDefines Defines() const override {
    if (fire_) return {{"FIRE", "1"}};
    return {};
  }

  bool Configure(fx::Effect& effect, const oit::MethodInfo& method, std::string* error) override {
    const ParticleSettings& ps = particles_->settings();
    effect.GetVariableByName("Seconds")->AsScalar()->SetFloat(ps.secondsPerUpdate);
    const float acceleration[4] = {ps.acceleration.x, ps.acceleration.y, ps.acceleration.z, 0};
    effect.GetVariableByName("Acceleration")->AsVector()->SetFloatVector(acceleration);
    effect.GetVariableByName("Size")->AsScalar()->SetFloat(ps.size);
    effect.GetVariableByName("Flame")->AsScalar()->SetFloat(fire_ ? 1.0f : 0.0f);
    effect.GetVariableByName("Puff")->AsShaderResource()->SetResource(puff_.Get());
    return method.order != oit::DrawOrder::BackToFront || CreateSortBuffers(error);
  }

  // ShadeTriangle reads the particles by index from the buffer the frame drew (the
  // deferred passes draw in submission order).
  void SetFrameVariables(fx::Effect& effect) override {
    effect.GetVariableByName("Particles")->AsShaderResource()->SetResource(particles_->currentRawView());
  }

  // The staging copy the particles are read back into and the vertex buffer of their sorted copy.
  bool CreateSortBuffers(std::string* error) {
    if (staging_) return true;
    const UINT bytes = particles_->capacity() * kParticleStride;
    BUFFER_DESC staging{bytes, USAGE_STAGING, 0, CPU_ACCESS_READ, 0, 0};
    BUFFER_DESC sorted{bytes, USAGE_DEFAULT, BIND_VERTEX_BUFFER, 0, 0, 0};
    if (FAILED(setup_.device->CreateBuffer(&staging, nullptr, staging_.GetAddressOf())) ||
        FAILED(setup_.device->CreateBuffer(&sorted, nullptr, sorted_.GetAddressOf()))) {
      *error = "smoke: creating the buffers of the sorted copy failed";
      return false;
    }
    return true;
  }

  // The reference order: the particles read back, sorted back to front by view
  // depth (stable, so ties keep buffer order) and uploaded; returns their buffer.
  Buffer* SortBackToFront(DeviceContext* ctx, const Camera& camera, UINT* count) {
    const ParticleSettings& ps = particles_->settings();
    ctx->CopyResource(staging_.Get(), particles_->current());
    std::vector<ParticleRecord> live;
    MAPPED_SUBRESOURCE mapped{};
    if (SUCCEEDED(ctx->Map(staging_.Get(), 0, MAP_READ, 0, &mapped))) {
      const auto* data = static_cast<const ParticleRecord*>(mapped.pData);
      // SO_STATISTICS of this frame's update (the frame driver counts for back-to-front methods).
      live.assign(data, data + std::min<uint64_t>(particles_->liveCount(), particles_->capacity()));
      ctx->Unmap(staging_.Get(), 0);
    }
    std::vector<float> depth(live.size());
    for (size_t i = 0; i < live.size(); ++i) {
      const ParticleRecord& p = live[i];
      float t = p.seedAge[1] * ps.secondsPerUpdate;
      glm::vec3 c = 0.5f * t * t * ps.acceleration + t * glm::vec3(p.velocity[0], p.velocity[1], p.velocity[2]) +
                    glm::vec3(p.origin[0], p.origin[1], p.origin[2]);
      depth[i] = ViewDepth(camera, c);
    }
    const std::vector<uint32_t> order = BackToFrontOrder(depth);
    std::vector<ParticleRecord> sorted(particles_->capacity());
    for (size_t i = 0; i < order.size(); ++i) sorted[i] = live[order[i]];
    ctx->UpdateSubresource(sorted_.Get(), 0, nullptr, sorted.data(), 0, 0);
    *count = UINT(order.size());
    return sorted_.Get();
  }

  bool fire_;
  std::unique_ptr<ParticleSystem> particles_;
  ComPtr<ShaderResourceView> puff_;
  ComPtr<Buffer> staging_, sorted_;
};

}  // namespace

std::unique_ptr<TranslucentObject> CreateSmoke(const ObjectSetup& setup, const ParticleSettings& particles, bool fire,
                                               std::string* error) {
  auto smoke = std::make_unique<Smoke>(setup, fire);
  if (!smoke->Initialize(particles, error)) return nullptr;
  return smoke;
}

}  // namespace renderer
