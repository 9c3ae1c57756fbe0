// The particle rule of shaders_hlsl/particle_rule.hlsli, in C++: the CPU model
// the GPU particle system is checked against.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace renderer {

inline uint32_t ParticleHash(uint32_t x) {
  x = (x ^ 61u) ^ (x >> 16);
  x *= 9u;
  x = x ^ (x >> 4);
  x *= 0x27d4eb2du;
  x = x ^ (x >> 15);
  return x;
}

inline uint32_t ChildSeed(uint32_t emitterSeed, uint32_t frame, uint32_t slot, uint32_t spawnPerFrame) {
  return ParticleHash(emitterSeed * 0x9E3779B9u + frame * spawnPerFrame + slot);
}

inline uint32_t ChildLifetime(uint32_t seed, uint32_t minLife, uint32_t lifeRange) {
  return minLife + seed % lifeRange;
}

struct ParticleRule {
  uint32_t emitters = 1000;
  uint32_t spawnPerFrame = 10;  // at most 16 (the update GS emits at most 17 vertices)
  uint32_t minLife = 50;
  uint32_t lifeRange = 100;
};

// The define an effect holding the update GS (shaders_hlsl/particle_update.hlsli) is
// loaded with for this rule: the GS then declares no more output than the rule spawns,
// which sets its cost on a GPU.
inline std::pair<std::string, std::string> MaxSpawnPerUpdateDefine(const ParticleRule& rule) {
  return {"MAX_SPAWN_PER_UPDATE", std::to_string(rule.spawnPerFrame)};
}

// Counts live particles update by update without simulating each one: a child
// born in update f with lifetime L is alive after update F exactly when F - f < L.
class ParticleCountModel {
 public:
  explicit ParticleCountModel(const ParticleRule& rule) : rule_(rule) {}
  // Runs update `frame_ + 1` and returns the live particle count after it.
  uint64_t Step() {
    ++frame_;
    for (uint32_t e = 0; e < rule_.emitters; ++e) {
      for (uint32_t slot = 0; slot < rule_.spawnPerFrame; ++slot) {
        uint32_t life = ChildLifetime(ChildSeed(e, frame_, slot, rule_.spawnPerFrame), rule_.minLife, rule_.lifeRange);
        if (deaths_.size() <= frame_ + life) deaths_.resize(frame_ + life + 1, 0);
        ++deaths_[frame_ + life];
        ++alive_;
      }
    }
    if (frame_ < deaths_.size()) alive_ -= deaths_[frame_];
    return alive_ + rule_.emitters;
  }
  uint32_t frame() const { return frame_; }

 private:
  ParticleRule rule_;
  uint32_t frame_ = 0;
  uint64_t alive_ = 0;  // children
  std::vector<uint64_t> deaths_;
};

}  // namespace renderer
