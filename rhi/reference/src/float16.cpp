#include "rhi_reference/float16.h"

#include <bit>
#include <cmath>

namespace rhi::reference {
namespace {

constexpr uint32_t kFloatExponentMask = 0x7F800000u;
constexpr uint32_t kFloatMantissaMask = 0x007FFFFFu;
constexpr uint16_t kHalfQuietNaN = 0x7E00;

// Drops the low `shift` bits of `value`, rounding as asked. Round-to-nearest-even
// rounds up past the halfway point, and at exactly halfway only when the kept
// part is odd. A carry out of the mantissa moves into the exponent, which is
// what float16 wants (e.g. the largest denorm rounds up to the smallest normal).
uint32_t ShiftRightRounded(uint32_t value, uint32_t shift, HalfRounding rounding) {
  if (shift >= 32) return 0;  // smaller than half of the smallest float16 denorm
  const uint32_t kept = value >> shift;
  if (rounding == HalfRounding::TowardZero || shift == 0) return kept;
  const uint32_t dropped = value & ((1u << shift) - 1u);
  const uint32_t halfway = 1u << (shift - 1u);
  const bool roundUp = dropped > halfway || (dropped == halfway && (kept & 1u) != 0);
  return kept + (roundUp ? 1u : 0u);
}

}  // namespace

uint16_t FloatToHalf(float value, HalfRounding rounding) {
  const uint32_t bits = std::bit_cast<uint32_t>(value);
  const uint16_t sign = static_cast<uint16_t>((bits >> 16) & 0x8000u);
  const uint32_t exponentBits = bits & kFloatExponentMask;
  const uint32_t mantissa = bits & kFloatMantissaMask;

  if (exponentBits == kFloatExponentMask) {  // INF stays INF, NaN stays NaN (FS 3.2.2)
    if (mantissa == 0) return sign | kHalfInfinity;
    const uint16_t payload = static_cast<uint16_t>(mantissa >> 13);
    return sign | kHalfInfinity | (payload != 0 ? payload : kHalfQuietNaN);
  }
  // float32 denorms (< 2^-126) are far below the smallest float16 denorm
  // (2^-24): they become a signed zero under either rounding.
  if (exponentBits == 0) return sign;

  const int exponent = static_cast<int>(exponentBits >> 23) - 127;
  if (exponent > 15) {  // |value| >= 65536: beyond the float16 range
    return rounding == HalfRounding::TowardZero ? (sign | kHalfMaxFinite) : (sign | kHalfInfinity);
  }
  if (exponent >= -14) {  // a float16 normal: keep 10 of the 23 mantissa bits
    const uint32_t exponentAndMantissa =
        (static_cast<uint32_t>(exponent + 15) << 23) | mantissa;  // 5-bit exponent, 23-bit mantissa
    const uint32_t half = ShiftRightRounded(exponentAndMantissa, 13, rounding);
    // Rounding 65504 < |value| < 65536 up reaches 0x7C00 = INF (IEEE); toward
    // zero never rounds up.
    return static_cast<uint16_t>(sign | half);
  }
  // A float16 denorm: value = significand * 2^(exponent-23), and the denorm
  // unit is 2^-24, so the count of units is significand >> (-exponent - 1).
  const uint32_t significand = mantissa | 0x00800000u;
  const uint32_t shift = static_cast<uint32_t>(-exponent - 1);
  return static_cast<uint16_t>(sign | ShiftRightRounded(significand, shift, rounding));
}

float HalfToFloat(uint16_t bits) {
  const bool negative = (bits & 0x8000u) != 0;
  const int exponent = (bits >> 10) & 0x1F;
  const int fraction = bits & 0x3FF;
  float magnitude = 0.0f;
  if (exponent == 31) {  // (a) NaN, (b) INF
    if (fraction != 0) {
      // Keep the payload: a NaN converts back to the same float16 bits.
      const uint32_t nan = 0x7F800000u | (static_cast<uint32_t>(fraction) << 13);
      return std::bit_cast<float>(nan | (negative ? 0x80000000u : 0u));
    }
    magnitude = INFINITY;
  } else if (exponent == 0) {  // (d) denorm 2^-14 * 0.f, (e) zero
    magnitude = std::ldexp(static_cast<float>(fraction), -24);
  } else {  // (c) 2^(e-15) * 1.f
    magnitude = std::ldexp(static_cast<float>(1024 + fraction), exponent - 25);
  }
  return negative ? -magnitude : magnitude;
}

}  // namespace rhi::reference
