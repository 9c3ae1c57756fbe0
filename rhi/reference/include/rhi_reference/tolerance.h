// How far a GPU result may be from the reference and still conform, per format
// and channel, in steps of the stored representation (UNORM codes, float ULPs).
// The derivation of each number is in tolerance.cpp.
#pragma once

#include <array>
#include <cstdint>

#include "rhi/d3d11_types.h"
#include "rhi_reference/formats.h"

namespace rhi::reference {

struct FormatTolerance {
  std::array<uint32_t, 4> steps{};  // RGBA; 0 = exact; absent channels are never compared
  const char* reason = "";          // the FS sections the numbers come from
};

// Tolerance for blended (or plain written) output on `format`.
FormatTolerance Tolerance(DXGI_FORMAT format);

// Distance between two stored values of one channel, in steps: |a-b| for UNORM /
// sRGB / UINT codes; for floats the number of representable values between them
// (+0 and -0 count as one). NaN matches only NaN and INF only the same INF: any
// other pairing is kIncomparable.
inline constexpr uint32_t kIncomparable = UINT32_MAX;
uint32_t StoredDistance(DXGI_FORMAT format, int channel, uint32_t a, uint32_t b);

// Every channel the format has is within Tolerance(format).
bool WithinTolerance(DXGI_FORMAT format, const StoredColor& expected, const StoredColor& actual);

}  // namespace rhi::reference
