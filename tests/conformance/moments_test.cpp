// Document 003's moment mathematics (shaders_hlsl/oit/moments.hlsli) evaluated on the
// GPU by a compute shader that includes the file itself, against CPU expectations:
//  - robustness: thousands of random fragment sets (one fragment, which makes the Hankel
//    matrix singular, fragments at one depth, opacities 0 and 1, depths at the ends of
//    the warp) accumulate their moments as the additive blend does and reconstruct the
//    transmittance in front of every fragment and of random depths: every value is
//    finite and within [exp(-b0), 1] (so within [0, 1]);
//  - the reconstruction: for one fragment and for two far apart, the transmittance
//    the moment bound gives (CPU, in closed form below) within 0.03;
//  - depth units: ViewDepthFromWindow inverts glm::perspectiveLH_ZO's window depth for
//    several near and far planes, and the correction of a surface 0.005 scene units
//    behind the nearest is m * 0.005 whatever the planes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "oit_fixture.h"

namespace {

using namespace conf;

constexpr int kMaxFragments = 8;
constexpr int kQueries = 4;
constexpr int kOutputsPerSet = kMaxFragments + kQueries + 1;  // T at each fragment, at each query, b0

struct FragmentSet {  // the structured-buffer element
  float depth[kMaxFragments];  // warped depths in [-1, 1]
  float alpha[kMaxFragments];
  float query[kQueries];  // more warped depths to reconstruct at
  uint32_t count;
  uint32_t pad[3];
};
static_assert(sizeof(FragmentSet) == 96);

// Moments summed as the moment pass's ONE/ONE blend sums them, then the reconstruction
// at every fragment and query.
std::vector<float> Reconstruct(Gpu& gpu, const std::vector<FragmentSet>& sets) {
  const std::string cs = ShaderSource("oit/moments.hlsli") + R"(
struct FragmentSet { float4 depth[2]; float4 alpha[2]; float4 query; uint count, pad0, pad1, pad2; };
StructuredBuffer<FragmentSet> Sets : register(t0);
RWStructuredBuffer<float> Out : register(u0);
[numthreads(1, 1, 1)] void main(uint3 id : SV_DispatchThreadID) {
  FragmentSet s = Sets[id.x];
  float b0 = 0.0;
  float4 b = 0.0;
  for (uint i = 0; i < s.count; ++i) {
    float f0;
    float4 f;
    PowerMoments(s.depth[i / 4][i % 4], OpticalDepth(s.alpha[i / 4][i % 4]), f0, f);
    b0 += f0;
    b += f;
  }
  uint o = id.x * 13;
  for (uint k = 0; k < 8; ++k) Out[o + k] = k < s.count ? TransmittanceInFront(b0, b, s.depth[k / 4][k % 4]) : 1.0;
  for (uint q = 0; q < 4; ++q) Out[o + 8 + q] = TransmittanceInFront(b0, b, s.query[q]);
  Out[o + 12] = b0;
}
)";
  return RunFloatCompute(gpu, cs, sets.data(), sizeof(FragmentSet), UINT(sets.size()),
                         UINT(sets.size() * kOutputsPerSet));
}

FragmentSet RandomSet(std::mt19937& rng, int kind) {
  auto u = [&](float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng); };
  FragmentSet s{};
  s.count = kind == 0 ? 1u : 1u + rng() % kMaxFragments;
  const float shared = u(-1, 1);
  for (uint32_t i = 0; i < s.count; ++i) {
    switch (kind) {
      case 1: s.depth[i] = shared; break;                                 // all at one depth
      case 2: s.depth[i] = (rng() & 1) ? -1.0f : 1.0f; break;             // the ends of the warp
      case 3: s.depth[i] = shared + u(-1e-4f, 1e-4f); break;              // closer than the bias resolves
      default: s.depth[i] = u(-1, 1);
    }
    const int opacity = int(rng() % 8);
    s.alpha[i] = opacity == 0 ? 0.0f : opacity == 1 ? 1.0f : opacity == 2 ? u(0, 1e-3f) : u(0, 1);
  }
  for (float& q : s.query) q = u(-1, 1);
  return s;
}

TEST(Moments, RandomFragmentSetsReconstructFiniteTransmittanceWithinZeroOne) {
  Gpu gpu(nullptr, true);
  ASSERT_TRUE(gpu.ok());
  std::mt19937 rng(2018);
  std::vector<FragmentSet> sets;
  for (int i = 0; i < 4000; ++i) sets.push_back(RandomSet(rng, i % 5));
  const std::vector<float> out = Reconstruct(gpu, sets);
  int singular = 0;
  for (size_t i = 0; i < sets.size(); ++i) {
    const float b0 = out[i * kOutputsPerSet + kMaxFragments + kQueries];
    singular += sets[i].count == 1;
    for (int k = 0; k < kMaxFragments + kQueries; ++k) {
      const float t = out[i * kOutputsPerSet + k];
      ASSERT_TRUE(std::isfinite(t)) << "set " << i << " value " << k;
      ASSERT_GE(t, 0.0f) << "set " << i << " value " << k;
      ASSERT_LE(t, 1.0f) << "set " << i << " value " << k;
      // Nothing lets through less than everything the pixel holds (a float's rounding aside).
      ASSERT_GE(t, std::exp(-b0) * (1.0f - 1e-5f)) << "set " << i << " value " << k << " b0 " << b0;
    }
  }
  EXPECT_GE(singular, 800) << "one-fragment sets (a singular Hankel matrix)";
  for (const std::string& m : gpu.validation()) ADD_FAILURE() << "validation layer: " << m;
}

// The moment bound where the fragments are far apart (CPU, closed form): the
// absorbance of what lies in front counts fully, that at the queried depth with the
// overestimation 0.25 (moments.hlsli's kOverestimation), what lies behind not at all.
TEST(Moments, FarApartFragmentsReconstructTheBound) {
  Gpu gpu(nullptr, true);
  ASSERT_TRUE(gpu.ok());
  const float kOverestimation = 0.25f;
  FragmentSet one{}, two{};
  one.count = 1, one.depth[0] = 0.2f, one.alpha[0] = 0.6f;
  one.query[0] = -0.8f, one.query[1] = 0.9f;
  two.count = 2, two.depth[0] = 0.6f, two.alpha[0] = 0.4f, two.depth[1] = -0.5f, two.alpha[1] = 0.5f;
  two.query[0] = -0.9f, two.query[1] = 0.95f;
  const std::vector<float> out = Reconstruct(gpu, {one, two});
  const float* a = &out[0];
  const float* b = &out[kOutputsPerSet];
  EXPECT_NEAR(a[0], std::pow(0.4f, kOverestimation), 0.03f) << "one fragment at its own depth";
  EXPECT_NEAR(a[kMaxFragments + 0], 1.0f, 0.03f) << "in front of it";
  EXPECT_NEAR(a[kMaxFragments + 1], 0.4f, 0.03f) << "behind it";
  EXPECT_NEAR(b[1], std::pow(0.5f, kOverestimation), 0.03f) << "the nearer of two";
  EXPECT_NEAR(b[0], 0.5f * std::pow(0.6f, kOverestimation), 0.03f) << "the farther of two";
  EXPECT_NEAR(b[kMaxFragments + 0], 1.0f, 0.03f) << "in front of both";
  EXPECT_NEAR(b[kMaxFragments + 1], 0.5f * 0.6f, 0.03f) << "behind both";
}

// z and z_min are view depths in scene units: the window depth goes back to the view
// depth it came from for any planes, and so the correction of a surface 0.005 behind
// the nearest is 100 * 0.005 = 0.5 for near/far 0.25/5000 (document 003's) as for
// 0.05/100 and 1/50, where the window depths of the two surfaces differ by factors of
// ten (the mistake of comparing window depths with a view-depth slope).
TEST(Moments, TheCorrectionComparesViewDepthsWhateverTheNearAndFarPlanes) {
  Gpu gpu(nullptr, true);
  ASSERT_TRUE(gpu.ok());
  struct Case {
    float nearPlane, farPlane, viewDepth, windowDepth, windowDepthBehind;
  };
  std::vector<Case> cases;
  // glm::perspectiveLH_ZO's depth: z = f / (f - n) - f n / ((f - n) d), here in double.
  const auto window = [](double n, double f, double d) { return float(f / (f - n) - f * n / ((f - n) * d)); };
  for (auto [n, f] : {std::pair{0.25f, 5000.0f}, std::pair{0.05f, 100.0f}, std::pair{1.0f, 50.0f}})
    for (float d : {1.5f, 2.5f, 4.0f})
      cases.push_back({n, f, d, window(n, f, d), window(n, f, d + 0.005)});
  const std::string cs = ShaderSource("oit/moments.hlsli") + R"(
struct Case { float nearPlane, farPlane, viewDepth, windowDepth, windowDepthBehind; };
StructuredBuffer<Case> Cases : register(t0);
RWStructuredBuffer<float> Out : register(u0);
[numthreads(1, 1, 1)] void main(uint3 id : SV_DispatchThreadID) {
  Case c = Cases[id.x];
  float z = ViewDepthFromWindow(c.windowDepthBehind, c.nearPlane, c.farPlane);
  float zMin = ViewDepthFromWindow(c.windowDepth, c.nearPlane, c.farPlane);
  Out[id.x * 3 + 0] = zMin;
  Out[id.x * 3 + 1] = MinDepthCorrection(z, zMin, 100.0);
  Out[id.x * 3 + 2] = MinDepthCorrection(zMin, zMin, 100.0);
}
)";
  const std::vector<float> out =
      RunFloatCompute(gpu, cs, cases.data(), sizeof(Case), UINT(cases.size()), UINT(cases.size() * 3));
  for (size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    SCOPED_TRACE("near " + std::to_string(c.nearPlane) + " far " + std::to_string(c.farPlane) + " depth " +
                 std::to_string(c.viewDepth) + ": window depths differ by " +
                 std::to_string(c.windowDepthBehind - c.windowDepth));
    EXPECT_NEAR(out[i * 3 + 0], c.viewDepth, 1e-4f * c.viewDepth) << "view depth from window depth";
    EXPECT_NEAR(out[i * 3 + 1], 0.5f, 0.02f) << "m (z - z_min) for a surface 0.005 behind";
    EXPECT_EQ(out[i * 3 + 2], 1.0f) << "the nearest surface keeps its weight";
  }
  for (const std::string& m : gpu.validation()) ADD_FAILURE() << "validation layer: " << m;
}

}  // namespace
