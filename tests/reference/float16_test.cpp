// float32 <-> float16. Expected bit patterns worked out by hand: a float16 is
// sign | 5-bit exponent (bias 15) | 10-bit fraction; denorms are fraction * 2^-24.
#include <gtest/gtest.h>

#include <cmath>

#include "rhi_reference/float16.h"

namespace rhi::reference {
namespace {

constexpr auto kZero = HalfRounding::TowardZero;
constexpr auto kEven = HalfRounding::NearestEven;

TEST(Float16, ExactValuesAreTheSameUnderBothRoundings) {
  // 1.0 = 2^0 * 1.0: exponent 15 -> 0x3C00. 2.5 = 2^1 * 1.25: 0x4000 | 0x100.
  EXPECT_EQ(FloatToHalf(1.0f, kZero), 0x3C00);
  EXPECT_EQ(FloatToHalf(2.5f, kEven), 0x4100);
  // -2.0: sign | exponent 16 -> 0xC000. 65504 = 2^15 * (1 + 1023/1024) -> 0x7BFF.
  EXPECT_EQ(FloatToHalf(-2.0f, kZero), 0xC000);
  EXPECT_EQ(FloatToHalf(65504.0f, kZero), 0x7BFF);
  EXPECT_EQ(FloatToHalf(65504.0f, kEven), 0x7BFF);
}

TEST(Float16, OneThird) {
  // 1/3 = 2^-2 * 1.0101010101|0101...: exponent 13 (0x3400) | 0x155; the dropped
  // bits 0101... are below half, so both roundings keep 0x3555 = 0.333251953125.
  EXPECT_EQ(FloatToHalf(1.0f / 3.0f, kZero), 0x3555);
  EXPECT_EQ(FloatToHalf(1.0f / 3.0f, kEven), 0x3555);
  EXPECT_EQ(HalfToFloat(0x3555), 0.333251953125f);
}

TEST(Float16, RoundingTiesAndBeyondHalf) {
  // 1 + 3/2048 is 1.5 float16 ULPs (ULP 1/1024) above 1: toward zero 0x3C01,
  // nearest-even goes up past the half to 0x3C02.
  EXPECT_EQ(FloatToHalf(1.0f + 3.0f / 2048.0f, kZero), 0x3C01);
  EXPECT_EQ(FloatToHalf(1.0f + 3.0f / 2048.0f, kEven), 0x3C02);
  // 1 + 1/2048 is exactly half an ULP: the tie goes to the even 0x3C00.
  EXPECT_EQ(FloatToHalf(1.0f + 1.0f / 2048.0f, kEven), 0x3C00);
  // 1 + 3/4096 is 0.75 ULP: toward zero 0x3C00, nearest 0x3C01.
  EXPECT_EQ(FloatToHalf(1.0f + 3.0f / 4096.0f, kZero), 0x3C00);
  EXPECT_EQ(FloatToHalf(1.0f + 3.0f / 4096.0f, kEven), 0x3C01);
}

TEST(Float16, OverflowIsMaxFiniteForD3DAndInfinityForIeee) {
  // 65520 is exactly halfway between 65504 and the next step 65536 (= INF's place).
  // D3D11 (FS 3.2.2, round toward zero, no INF): 0x7BFF. IEEE nearest-even: INF.
  EXPECT_EQ(FloatToHalf(65520.0f, kZero), 0x7BFF);
  EXPECT_EQ(FloatToHalf(65520.0f, kEven), 0x7C00);
  EXPECT_EQ(FloatToHalf(-65520.0f, kZero), 0xFBFF);
  EXPECT_EQ(FloatToHalf(-65520.0f, kEven), 0xFC00);
  // 65519 is below the halfway point: both 65504.
  EXPECT_EQ(FloatToHalf(65519.0f, kEven), 0x7BFF);
  // 1e6 and FLT_MAX: far out of range.
  EXPECT_EQ(FloatToHalf(1.0e6f, kZero), 0x7BFF);
  EXPECT_EQ(FloatToHalf(3.0e38f, kEven), 0x7C00);
}

TEST(Float16, InfinityNanAndSignedZero) {
  EXPECT_EQ(FloatToHalf(INFINITY, kZero), 0x7C00);   // INF stays INF (FS 3.2.2)
  EXPECT_EQ(FloatToHalf(-INFINITY, kZero), 0xFC00);
  EXPECT_EQ(FloatToHalf(NAN, kZero) & 0x7C00, 0x7C00);  // exponent all ones...
  EXPECT_NE(FloatToHalf(NAN, kZero) & 0x03FF, 0);       // ...and a non-zero fraction
  EXPECT_EQ(FloatToHalf(-0.0f, kZero), 0x8000);
  EXPECT_TRUE(std::isnan(HalfToFloat(0x7E00)));
  EXPECT_EQ(HalfToFloat(0xFC00), -INFINITY);
}

TEST(Float16, TinyValuesBecomeDenorms) {
  // Smallest denorm 2^-24 -> 0x0001; largest denorm 1023 * 2^-24 -> 0x03FF.
  EXPECT_EQ(FloatToHalf(std::ldexp(1.0f, -24), kZero), 0x0001);
  EXPECT_EQ(FloatToHalf(std::ldexp(1023.0f, -24), kEven), 0x03FF);
  EXPECT_EQ(FloatToHalf(-std::ldexp(1.0f, -24), kZero), 0x8001);
  // 1.5 * 2^-24: toward zero 1 unit, nearest-even rounds the tie up to 2 (even).
  EXPECT_EQ(FloatToHalf(std::ldexp(1.5f, -24), kZero), 0x0001);
  EXPECT_EQ(FloatToHalf(std::ldexp(1.5f, -24), kEven), 0x0002);
  // 2^-25 is half a unit: toward zero 0, nearest-even ties to the even 0.
  EXPECT_EQ(FloatToHalf(std::ldexp(1.0f, -25), kZero), 0x0000);
  EXPECT_EQ(FloatToHalf(std::ldexp(1.0f, -25), kEven), 0x0000);
  // 0.75 * 2^-24: toward zero 0, nearest 1.
  EXPECT_EQ(FloatToHalf(std::ldexp(0.75f, -24), kZero), 0x0000);
  EXPECT_EQ(FloatToHalf(std::ldexp(0.75f, -24), kEven), 0x0001);
  // 1023.75 units rounds up into the smallest normal 2^-14 = 0x0400.
  EXPECT_EQ(FloatToHalf(std::ldexp(1023.75f, -24), kEven), 0x0400);
  // A float32 denorm (1e-40) is far below 2^-25: zero, sign kept.
  EXPECT_EQ(FloatToHalf(-1.0e-40f, kEven), 0x8000);
  EXPECT_EQ(HalfToFloat(0x0001), std::ldexp(1.0f, -24));
  EXPECT_EQ(HalfToFloat(0x03FF), std::ldexp(1023.0f, -24));
}

TEST(Float16, EveryHalfSurvivesTheRoundTrip) {
  // Every float16 is exactly a float32, so half -> float -> half is the identity
  // under either rounding (NaN payloads included).
  for (uint32_t bits = 0; bits <= 0xFFFF; ++bits) {
    const uint16_t half = static_cast<uint16_t>(bits);
    ASSERT_EQ(FloatToHalf(HalfToFloat(half), kZero), half) << std::hex << bits;
    ASSERT_EQ(FloatToHalf(HalfToFloat(half), kEven), half) << std::hex << bits;
  }
}

}  // namespace
}  // namespace rhi::reference
