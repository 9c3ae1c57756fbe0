// The GPU particle system's spawn/kill rule against the CPU model, on a size
// CI can afford; `particles_check` runs the 1M-particle, 1000-update version.
#include "gpu_test.h"
#include "particle_check.h"

namespace rhi_test {
namespace {

class ParticlesTest : public GpuTest {};

TEST_F(ParticlesTest, CountMatchesTheCpuModelEveryUpdateFor1000Updates) {
  renderer::ParticleSettings settings;
  settings.rule = {20, 4, 20, 40};  // ~20 * 4 * 40 = 3.2k particles at steady state
  auto result = particles_check::RunParticleCheck(device.Get(), context.Get(), settings, 1000, 1);
  EXPECT_TRUE(result.ok) << result.failure;
  EXPECT_EQ(result.updates, 1000u);
  EXPECT_GT(result.lastCount, 2000u) << "steady state reached";
}

TEST_F(ParticlesTest, OverflowIsReportedNotHidden) {
  renderer::ParticleSettings settings;
  settings.rule = {10, 4, 20, 40};
  settings.capacity = 100;  // far below the ~1.6k the rule reaches
  auto result = particles_check::RunParticleCheck(device.Get(), context.Get(), settings, 100, 1);
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.failure.find("of"), std::string::npos);
}

}  // namespace
}  // namespace rhi_test
