// particles_check [--emitters N] [--spawn K] [--min-life L] [--life-range R] [--updates U] [--every E]
// Runs the GPU particle system on the chosen Vulkan device (RHI_DEVICE) and
// checks its particle count against the CPU model. Defaults: the 1M-particle,
// 1000-update run of the stream-output issue.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "particle_check.h"

int main(int argc, char** argv) {
  renderer::ParticleSettings settings;
  settings.rule = {1000, 10, 50, 100};
  uint32_t updates = 1000, every = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    uint32_t value = static_cast<uint32_t>(std::strtoul(argv[i + 1], nullptr, 10));
    if (!std::strcmp(argv[i], "--emitters")) settings.rule.emitters = value;
    else if (!std::strcmp(argv[i], "--spawn")) settings.rule.spawnPerFrame = value;
    else if (!std::strcmp(argv[i], "--min-life")) settings.rule.minLife = value;
    else if (!std::strcmp(argv[i], "--life-range")) settings.rule.lifeRange = value;
    else if (!std::strcmp(argv[i], "--updates")) updates = value;
    else if (!std::strcmp(argv[i], "--every")) every = value;
    else {
      std::fprintf(stderr, "unknown option %s\n", argv[i]);
      return 2;
    }
  }
  rhi::ComPtr<rhi::Device> device;
  rhi::ComPtr<rhi::DeviceContext> context;
  if (rhi::FAILED(rhi::CreateDevice(nullptr, device.GetAddressOf(), context.GetAddressOf()))) return 1;
  auto start = std::chrono::steady_clock::now();
  auto result = particles_check::RunParticleCheck(device.Get(), context.Get(), settings, updates, every);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%s: %u updates checked, %llu particles after the last, %.1f s on %s\n",
              result.ok ? "OK" : "FAILED", result.updates, static_cast<unsigned long long>(result.lastCount), seconds,
              device->GetAdapterName());
  if (!result.ok) std::printf("%s\n", result.failure.c_str());
  return result.ok ? 0 : 1;
}
