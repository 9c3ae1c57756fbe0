// The tolerance table and the stored-value comparison.
#include <gtest/gtest.h>

#include "rhi_reference/float16.h"
#include "rhi_reference/tolerance.h"

namespace rhi::reference {
namespace {

using Steps = std::array<uint32_t, 4>;

TEST(Tolerance, Table) {
  EXPECT_EQ(Tolerance(DXGI_FORMAT_R8G8B8A8_UNORM).steps, (Steps{1, 1, 1, 1}));
  EXPECT_EQ(Tolerance(DXGI_FORMAT_B8G8R8A8_UNORM).steps, (Steps{1, 1, 1, 1}));
  EXPECT_EQ(Tolerance(DXGI_FORMAT_R10G10B10A2_UNORM).steps, (Steps{1, 1, 1, 1}));
  EXPECT_EQ(Tolerance(DXGI_FORMAT_R8G8B8A8_UNORM_SRGB).steps, (Steps{2, 2, 2, 1}));
  EXPECT_EQ(Tolerance(DXGI_FORMAT_R16G16B16A16_FLOAT).steps, (Steps{2, 2, 2, 2}));
  EXPECT_EQ(Tolerance(DXGI_FORMAT_R32_FLOAT).steps, (Steps{2, 2, 2, 2}));
  EXPECT_EQ(Tolerance(DXGI_FORMAT_R32G32B32A32_UINT).steps, (Steps{0, 0, 0, 0}));
  EXPECT_NE(std::string(Tolerance(DXGI_FORMAT_R8_UNORM).reason).find("3.2.3.6"), std::string::npos);
}

TEST(Tolerance, UnormCodes) {
  // 128 vs 129: 1 step, inside; 128 vs 130: 2 steps, outside.
  const StoredColor expected{{128, 128, 128, 128}};
  EXPECT_TRUE(WithinTolerance(DXGI_FORMAT_R8G8B8A8_UNORM, expected, StoredColor{{129, 127, 128, 128}}));
  EXPECT_FALSE(WithinTolerance(DXGI_FORMAT_R8G8B8A8_UNORM, expected, StoredColor{{130, 128, 128, 128}}));
  // sRGB: 2 steps allowed on colour, 1 on alpha.
  EXPECT_TRUE(WithinTolerance(DXGI_FORMAT_R8G8B8A8_UNORM_SRGB, expected, StoredColor{{130, 126, 128, 129}}));
  EXPECT_FALSE(WithinTolerance(DXGI_FORMAT_R8G8B8A8_UNORM_SRGB, expected, StoredColor{{128, 128, 128, 130}}));
}

TEST(Tolerance, AbsentChannelsAreIgnored) {
  // R8_UNORM compares R only; B8G8R8X8 never compares the X byte.
  EXPECT_TRUE(WithinTolerance(DXGI_FORMAT_R8_UNORM, StoredColor{{7, 0, 0, 0}}, StoredColor{{7, 99, 99, 99}}));
  EXPECT_TRUE(WithinTolerance(DXGI_FORMAT_B8G8R8X8_UNORM, StoredColor{{1, 2, 3, 0}}, StoredColor{{1, 2, 3, 255}}));
}

TEST(Tolerance, FloatUlps) {
  // float16 1.0 = 0x3C00: 0x3C02 is 2 ULPs away (inside), 0x3C03 three (outside);
  // across zero, 0x0001 and 0x8001 are 2 steps apart (+0 and -0 count once).
  constexpr DXGI_FORMAT kHalf = DXGI_FORMAT_R16_FLOAT;
  EXPECT_EQ(StoredDistance(kHalf, 0, 0x3C00, 0x3C02), 2u);
  EXPECT_TRUE(WithinTolerance(kHalf, StoredColor{{0x3C00, 0, 0, 0}}, StoredColor{{0x3C02, 0, 0, 0}}));
  EXPECT_FALSE(WithinTolerance(kHalf, StoredColor{{0x3C00, 0, 0, 0}}, StoredColor{{0x3C03, 0, 0, 0}}));
  EXPECT_EQ(StoredDistance(kHalf, 0, 0x0001, 0x8001), 2u);
  EXPECT_EQ(StoredDistance(kHalf, 0, 0x0000, 0x8000), 0u);
  // float32 1.0 = 0x3F800000 vs 0x3F800002: 2 steps.
  EXPECT_EQ(StoredDistance(DXGI_FORMAT_R32_FLOAT, 0, 0x3F800000u, 0x3F800002u), 2u);
}

TEST(Tolerance, InfinityAndNan) {
  constexpr DXGI_FORMAT kHalf = DXGI_FORMAT_R16_FLOAT;
  // D3D11 stores 65504 where IEEE gives INF: a device that writes INF is out.
  EXPECT_EQ(StoredDistance(kHalf, 0, kHalfMaxFinite, kHalfInfinity), kIncomparable);
  EXPECT_FALSE(WithinTolerance(kHalf, StoredColor{{kHalfMaxFinite, 0, 0, 0}}, StoredColor{{kHalfInfinity, 0, 0, 0}}));
  EXPECT_EQ(StoredDistance(kHalf, 0, kHalfInfinity, kHalfInfinity), 0u);
  EXPECT_EQ(StoredDistance(kHalf, 0, 0x7E00, 0x7C01), 0u);  // any NaN matches any NaN
  EXPECT_EQ(StoredDistance(kHalf, 0, 0x7E00, 0x3C00), kIncomparable);
}

TEST(Tolerance, UintIsExact) {
  EXPECT_TRUE(WithinTolerance(DXGI_FORMAT_R32_UINT, StoredColor{{42, 0, 0, 0}}, StoredColor{{42, 0, 0, 0}}));
  EXPECT_FALSE(WithinTolerance(DXGI_FORMAT_R32_UINT, StoredColor{{42, 0, 0, 0}}, StoredColor{{43, 0, 0, 0}}));
}

}  // namespace
}  // namespace rhi::reference
