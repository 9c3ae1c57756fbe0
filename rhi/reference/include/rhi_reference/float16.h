// float32 <-> float16 conversion, written out so the rounding is visible.
//
// Which rounding D3D11 uses when a float32 is stored to a float16 render target:
// FS 3.2.2 "Floating Point Conversion": "Round-to-zero must be used during
// conversion to another float format", and "for source values greater than the
// dynamic range of a lower range target format (eg. a large 32-bit float value is
// written into a 16-bit float RenderTarget), the maximum representable
// (appropriately signed) value results, NOT including signed infinity". INF stays
// INF, NaN stays NaN, and float16 keeps denorms (FS 3.1.5).
// So D3D11 gives TowardZero; NearestEven is IEEE 754 (what most CPU libraries
// and many GPUs do) and is here to compare against.
#pragma once

#include <cstdint>

namespace rhi::reference {

enum class HalfRounding {
  TowardZero,   // FS 3.2.2: D3D11 float -> float16 conversion; overflow -> +-65504
  NearestEven,  // IEEE 754 default; overflow -> +-INF
};

uint16_t FloatToHalf(float value, HalfRounding rounding);

// Exact (every float16 is a float32): FS 3.1.5 cases (a)-(e).
float HalfToFloat(uint16_t bits);

inline constexpr uint16_t kHalfMaxFinite = 0x7BFF;  // 65504
inline constexpr uint16_t kHalfInfinity = 0x7C00;

}  // namespace rhi::reference
