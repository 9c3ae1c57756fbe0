#include "particle_check.h"

#include "rhi/query_wait.h"

namespace particles_check {

using namespace rhi;

CheckResult RunParticleCheck(Device* device, DeviceContext* context, const renderer::ParticleSettings& settings,
                             uint32_t updates, uint32_t queryEvery) {
  CheckResult result;
  std::string error;
  auto system = renderer::ParticleSystem::Create(device, settings, &error);
  if (!system) return {false, 0, 0, error};
  ComPtr<Query> stats;
  QUERY_DESC desc{QUERY_SO_STATISTICS_STREAM0, 0};
  if (FAILED(device->CreateQuery(&desc, stats.GetAddressOf()))) return {false, 0, 0, "CreateQuery failed"};
  renderer::ParticleCountModel model(settings.rule);
  for (uint32_t update = 1; update <= updates; ++update) {
    const uint64_t expected = model.Step();
    const bool check = update % queryEvery == 0 || update == updates;
    if (check) context->Begin(stats.Get());
    system->Update(context);
    if (!check) continue;
    context->End(stats.Get());
    QUERY_DATA_SO_STATISTICS data{};
    if (FAILED(WaitForData(context, stats.Get(), &data))) return {false, update, 0, "GetData(SO_STATISTICS) failed"};
    result.updates = update;
    result.lastCount = data.NumPrimitivesWritten;
    if (data.NumPrimitivesWritten != expected || data.PrimitivesStorageNeeded != expected) {
      result.ok = false;
      result.failure = "update " + std::to_string(update) + ": GPU wrote " +
                       std::to_string(data.NumPrimitivesWritten) + " of " +
                       std::to_string(data.PrimitivesStorageNeeded) + " particles, the CPU model has " +
                       std::to_string(expected);
      return result;
    }
  }
  return result;
}

}  // namespace particles_check
