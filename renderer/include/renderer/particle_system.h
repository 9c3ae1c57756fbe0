// The GPU particle system of document 000: particles live only on the GPU,
// updated each frame by a geometry shader whose output is streamed into one of
// two buffers (ping-pong), and drawn with DrawAuto because the CPU never knows
// how many survived. Both passes are techniques of shaders_hlsl/particles.fx.
#pragma once

#include <array>
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "fx/effect.h"
#include "renderer/particle_rule.h"
#include "rhi/rhi.h"

namespace renderer {

struct ParticleSettings {
  ParticleRule rule;
  uint32_t capacity = 0;  // particles per buffer; 0: the most the rule can reach
  glm::vec3 emitterCenter{0, 0, 0};
  float emitterRadius = 2.0f;
  glm::vec3 spread{0.3f, 0.1f, 0.3f};  // random initial velocity range (units per second)
  float speedUp = 1.0f;
  glm::vec3 acceleration{0.2f, 0.15f, 0.0f};  // wind and buoyancy
  float secondsPerUpdate = 1.0f / 60.0f;
  float size = 0.15f;
};

struct Camera {
  glm::mat4 viewProj{1.0f};  // column-vector convention: clip = viewProj * world
  glm::vec3 eye{0, 0, 0};
  // The projection's near and far planes (view depth, scene units), which viewProj's
  // perspectiveLH_ZO was made with.
  float nearPlane = 0.1f, farPlane = 40.0f;
};

class ParticleSystem {
 public:
  static std::unique_ptr<ParticleSystem> Create(rhi::Device* device, const ParticleSettings& settings,
                                                std::string* error);

  // One update pass: the current buffer in, the other out through stream output.
  // countLive: an SO_STATISTICS query around it, read back (a wait) into liveCount().
  void Update(rhi::DeviceContext* context, bool countLive = false);
  // Billboards of the live particles with DrawAuto, through the effect's Alpha/Transparency pass (OVER
  // blending, depth tested and not written, no culling) into the caller's targets.
  void Draw(rhi::DeviceContext* context, const Camera& camera);

  // The buffer the last update wrote (what Draw draws).
  rhi::Buffer* current() const { return buffers_[current_].Get(); }
  // A raw view (ByteAddressBuffer) of it, for shaders that read particles by index.
  rhi::ShaderResourceView* currentRawView() const { return rawViews_[current_].Get(); }
  uint32_t updates() const { return updates_; }
  // Particles (emitters included) the last counting Update left alive.
  uint64_t liveCount() const { return liveCount_; }
  uint32_t capacity() const { return capacity_; }
  const ParticleSettings& settings() const { return settings_; }

 private:
  ParticleSystem() = default;
  bool Initialize(rhi::Device* device, const ParticleSettings& settings, std::string* error);
  void BindParticleInput(rhi::DeviceContext* context, rhi::Buffer* buffer);

  ParticleSettings settings_;
  uint32_t capacity_ = 0;
  uint32_t updates_ = 0;
  uint32_t current_ = 0;
  uint64_t liveCount_ = 0;
  rhi::ComPtr<rhi::Query> streamOutStatistics_;
  rhi::ComPtr<rhi::Buffer> emitters_;
  std::array<rhi::ComPtr<rhi::Buffer>, 2> buffers_;
  std::array<rhi::ComPtr<rhi::ShaderResourceView>, 2> rawViews_;
  rhi::ComPtr<rhi::InputLayout> layout_;
  rhi::ComPtr<fx::Effect> effect_;
  fx::EffectPass *updatePass_ = nullptr, *drawPass_ = nullptr;
  fx::EffectScalarVariable* frame_ = nullptr;
  fx::EffectMatrixVariable* viewProj_ = nullptr;
  fx::EffectVariable* eye_ = nullptr;
};

// Bytes per particle in the stream-output buffers.
inline constexpr uint32_t kParticleStride = 40;

// A particle as the stream-output buffers hold it (shaders_hlsl/particle.hlsli), for
// the CPU code that fills or reads them.
struct ParticleRecord {
  float origin[3];
  float velocity[3];
  uint32_t seedAge[2];   // x: seed, y: age in updates
  uint32_t kindLife[2];  // x: 0 emitter / 1 smoke; y: lifetime in updates
};
static_assert(sizeof(ParticleRecord) == kParticleStride);

}  // namespace renderer
