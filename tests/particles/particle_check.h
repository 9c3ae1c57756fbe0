// Runs the GPU particle system and compares its live particle count, update by
// update, with the CPU model of the same rule. The count comes from a
// SO_STATISTICS query around each update: NumPrimitivesWritten is the number
// of particles streamed out (one point each), and PrimitivesStorageNeeded must
// equal it (no overflow).
#pragma once

#include <cstdint>
#include <string>

#include "renderer/particle_system.h"

namespace particles_check {

struct CheckResult {
  bool ok = true;
  uint32_t updates = 0;
  uint64_t lastCount = 0;
  std::string failure;  // the first mismatch
};

// `queryEvery`: compare every n-th update (1: every update).
CheckResult RunParticleCheck(rhi::Device* device, rhi::DeviceContext* context,
                             const renderer::ParticleSettings& settings, uint32_t updates, uint32_t queryEvery);

}  // namespace particles_check
