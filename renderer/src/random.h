// Deterministic randomness of the demos: frame N is a pure function of the settings and N.
#pragma once

#include <cstdint>

#include "renderer/particle_rule.h"

namespace renderer {

// A hash of (seed, stream, index) -> [0, 1).
inline float Random(uint32_t seed, uint32_t stream, uint32_t index) {
  uint32_t x = ParticleHash(seed * 0x9E3779B9u ^ ParticleHash(stream * 0x85EBCA6Bu + index));
  x = ParticleHash(x + index);
  return (x >> 8) * (1.0f / 16777216.0f);
}

}  // namespace renderer
