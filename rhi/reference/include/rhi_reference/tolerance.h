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
//   |gpu - reference| <= bound(format, channel)
//
// UNORM, sRGB, float32: bound = k(format, channel) * unit(format, channel, m),
//   m = max(|Csrc*Fsrc|, |Cdst*Fdst|, |Csrc*Fsrc OP Cdst*Fdst|)   (BlendTerms),
//   widened for float32 and sRGB to the operands (OperandMagnitude, tolerance.cpp).
//   unit: one UNORM step 1/(2^bits-1) for UNORM (and sRGB alpha); the float32
//   ULP at m; for sRGB colour the linear size of the 8-bit sRGB step at m.
// float16: an error-propagation bound (Float16TermBound): the device may round
//   every blend input (source colour, blend factor, the factors' inputs and the
//   computed 1 - x) to float16 toward zero (FS 3.2.2), then multiply and add at
//   float16 precision (FS 3.1.5, FS 17.5); the bound adds up what each of those
//   roundings can move the result, from the magnitudes of this case's operands.
// The derivations are in tolerance.cpp. A channel conforms when it is within the
// stored-step table above OR (blend arithmetic only) within this bound; MIN /
// MAX, unblended writes and UINT keep the table alone.
struct TermBound {
  double k = 0;            // 0: the bound does not apply to this format / channel
  const char* reason = "";
  bool propagated = false; // float16: the bound is Float16TermBound (k is 1), not k * unit(m)
};
TermBound BlendTermK(DXGI_FORMAT format, int channel);

// m for one channel (0 when the channel had no blend arithmetic).
double TermMagnitude(const BlendTerms& terms, int channel);

// unit(format, channel, m) in linear float space (0 for UINT / absent channels).
double BlendUnit(DXGI_FORMAT format, int channel, double m);

// float16 targets: the most a conforming device's result and the reference's
// stored value may differ by, for one channel of ADD / SUBTRACT / REV_SUBTRACT
// (derivation in tolerance.cpp). 0 for channels without blend arithmetic.
double Float16TermBound(const BlendTerms& terms, int channel);

// float16 helpers of that bound, exposed for the tests: |x - RTZ16(x)| (0 when x
// is a float16 value; beyond 65504 the distance to 65504, FS 3.2.2), and the
// error bound of a blend factor computed at float16 precision from `source`.
double Float16ConversionError(double x);
double Float16FactorError(const FactorSource& source);

struct ChannelVerdict {
  uint32_t steps = 0;          // StoredDistance (kIncomparable: NaN / INF mismatch)
  bool withinTable = true;     // steps <= Tolerance(format).steps[channel]
  bool termBoundApplies = false;
  bool withinTermBound = false;
  double error = 0;            // |Decode(gpu) - Decode(reference)|, linear
  double m = 0;                // TermMagnitude
  double unit = 0;             // BlendUnit(format, channel, m)
  double bound = 0;            // k * unit, or Float16TermBound
  bool ok() const { return withinTable || (termBoundApplies && withinTermBound); }
  bool NeededTermBound() const { return !withinTable && termBoundApplies && withinTermBound; }
};

struct BlendVerdict {
  std::array<ChannelVerdict, 4> channels{};
  bool ok = true;               // every channel conforms
  bool usedTermBound = false;   // at least one channel passed only by the term bound
  // SRC_ALPHA_SAT with f outside [0, 1] (BlendOutput::hasSaturatedReading): the
  // pixel failed the FS 17.1 formula reading and matched the saturated one
  // (f clamped to [0, 1]); `channels` then describe the saturated reading.
  bool usedSaturatedReading = false;
};

// One reading of the reference against the device's pixel.
BlendVerdict CompareReading(DXGI_FORMAT format, const BlendReading& expected, const StoredColor& actual);

// The full check of a blended pixel against BlendResult's output: the formula
// reading, or (where BlendResult reports one) the saturated SRC_ALPHA_SAT reading.
BlendVerdict CompareBlend(DXGI_FORMAT format, const BlendOutput& expected, const StoredColor& actual);
inline bool WithinBlendTolerance(DXGI_FORMAT format, const BlendOutput& expected, const StoredColor& actual) {
  return CompareBlend(format, expected, actual).ok;
}

}  // namespace rhi::reference
