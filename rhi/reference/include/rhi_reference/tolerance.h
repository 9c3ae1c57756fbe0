// How far a GPU result may be from the reference and still conform, per format
// and channel, in steps of the stored representation (UNORM codes, float ULPs).
// The derivation of each number is in tolerance.cpp.
#pragma once

#include <array>
#include <cstdint>

#include "rhi/d3d11_types.h"
#include "rhi_reference/blend.h"
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

// ---------------------------------------------------------------------------
// The blend-term bound (for ADD / SUBTRACT / REV_SUBTRACT results only).
//
// Per channel, in linear float space (sRGB decoded):
//
//   |gpu - reference| <= k(format, channel) * unit(format, channel, m)
//   m = max(|Csrc*Fsrc|, |Cdst*Fdst|, |Csrc*Fsrc OP Cdst*Fdst|)   (BlendTerms)
//
// unit: one UNORM step 1/(2^bits-1) for UNORM (and sRGB alpha); the float32 or
// float16 ULP at magnitude m for float formats; for sRGB colour the linear size
// of the 8-bit sRGB step at linear magnitude m. FS 17.5 lets each product be
// rounded at the render target's precision before the op, and those roundings
// are at the magnitude of the products, not of the (possibly cancelled) result.
// The derivation of each k is in tolerance.cpp. A channel conforms when it is
// within the stored-step table above OR (blend arithmetic only) within this
// bound; MIN / MAX, unblended writes and UINT keep the table alone.
struct TermBound {
  double k = 0;            // 0: the bound does not apply to this format / channel
  const char* reason = "";
};
TermBound BlendTermK(DXGI_FORMAT format, int channel);

// m for one channel (0 when the channel had no blend arithmetic).
double TermMagnitude(const BlendTerms& terms, int channel);

// unit(format, channel, m) in linear float space (0 for UINT / absent channels).
double BlendUnit(DXGI_FORMAT format, int channel, double m);

struct ChannelVerdict {
  uint32_t steps = 0;          // StoredDistance (kIncomparable: NaN / INF mismatch)
  bool withinTable = true;     // steps <= Tolerance(format).steps[channel]
  bool termBoundApplies = false;
  bool withinTermBound = false;
  double error = 0;            // |Decode(gpu) - Decode(reference)|, linear
  double m = 0;                // TermMagnitude
  double unit = 0;             // BlendUnit(format, channel, m)
  double bound = 0;            // k * unit
  bool ok() const { return withinTable || (termBoundApplies && withinTermBound); }
  bool NeededTermBound() const { return !withinTable && termBoundApplies && withinTermBound; }
};

struct BlendVerdict {
  std::array<ChannelVerdict, 4> channels{};
  bool ok = true;               // every channel conforms
  bool usedTermBound = false;   // at least one channel passed only by the term bound
};

// The full check of a blended pixel against BlendResult's output.
BlendVerdict CompareBlend(DXGI_FORMAT format, const BlendOutput& expected, const StoredColor& actual);
inline bool WithinBlendTolerance(DXGI_FORMAT format, const BlendOutput& expected, const StoredColor& actual) {
  return CompareBlend(format, expected, actual).ok;
}

}  // namespace rhi::reference
