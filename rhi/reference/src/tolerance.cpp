#include "rhi_reference/tolerance.h"

#include <bit>
#include <cmath>
#include <cstdlib>

#include "rhi_reference/float16.h"

namespace rhi::reference {
namespace {

// How the numbers below are reached. The reference is the ideal result: inputs
// exact, blend in float32, one correctly rounded conversion. A device result is
// compared in steps of what is stored; |device - ideal| + |reference - ideal|
// bounds the distance, and a distance between two stored values is a whole number
// of steps, so "below 2" means "at most 1".
//
// UNORM (8-bit, R10G10B10A2 including its 2-bit alpha): FS 3.2.3.6 lets
// float->UNORM land within 0.6 ULP; FS 17.5 lets the blender work "at equal or
// more precision than the output format" (a rounding of up to 0.5 ULP inside the
// blend). Device <= 1.1 ULP, reference <= 0.5 ULP from the ideal: under 2 -> 1.
constexpr std::array<uint32_t, 4> kUnormSteps{1, 1, 1, 1};
constexpr const char* kUnormReason =
    "1 ULP: float->UNORM 0.6 ULP (FS 3.2.3.6) + blending at the RT's own precision (FS 17.5)";

// sRGB colour channels: the destination is decoded within 0.5 ULP on the sRGB
// side (FS 3.2.3.7), the result encoded within 0.6 ULP (FS 3.2.3.8), the blend
// itself may round at the RT's precision (FS 17.5, 0.5 ULP), and the reference
// is within 0.5 ULP: 2.1 -> 2. Blending in linear space keeps a destination
// decode error from growing when it is scaled by a factor <= 1, because the sRGB
// curve's slope grows no faster than the factor shrinks the error. Alpha is
// stored linear (FS 19.1.3.2): the UNORM rule.
constexpr std::array<uint32_t, 4> kSrgbSteps{2, 2, 2, 1};
constexpr const char* kSrgbReason =
    "RGB 2 ULP: sRGB->float 0.5 ULP (FS 3.2.3.7) + float->sRGB 0.6 ULP (FS 3.2.3.8) + blend "
    "rounding (FS 17.5); alpha 1 ULP as UNORM";

// float16: the blender may work in float16 or up to float32 (FS 17.5) and the
// steps of s*Fs OP d*Fd round to nearest (FS 3.1.5: 0.5 ULP, fused 0.6 ULP),
// about 1.5 ULP from the ideal when nothing cancels; the reference stores with
// round-toward-zero (FS 3.2.2, < 1 ULP). Together under 2.5 -> 2. This also
// admits a device that rounds to nearest-even where D3D11 says toward zero,
// except at overflow: D3D11 stores +-65504 where IEEE gives INF, and INF is
// never within tolerance of a finite value.
constexpr std::array<uint32_t, 4> kFloat16Steps{2, 2, 2, 2};
constexpr const char* kFloat16Reason =
    "2 ULP: fused float16 blend arithmetic (FS 3.1.5, FS 17.5) + round-toward-zero store (FS 3.2.2)";

// float32: each of the three roundings in s*Fs OP d*Fd is 0.5 ULP (FS 3.1.3);
// the device may fuse and reorder (FS 17.5: "considered fused") but must be no
// less accurate than the worst ordering. Reference and device each stay within
// about 1 ULP of the ideal when nothing cancels: 2.
constexpr std::array<uint32_t, 4> kFloat32Steps{2, 2, 2, 2};
constexpr const char* kFloat32Reason =
    "2 ULP: three float32 roundings of 0.5 ULP each, fused or reordered (FS 3.1.3, FS 17.5)";

// UINT: no blending, no conversion; the bits written are the bits the shader output.
constexpr std::array<uint32_t, 4> kExactSteps{0, 0, 0, 0};
constexpr const char* kUintReason = "exact: integer targets are written without blending or conversion";

// Note for every float tolerance: it holds when the blend does not cancel.
// SUBTRACT / REV_SUBTRACT of nearly equal terms leaves the absolute error of the
// terms on a small result, many ULPs of it; fixtures should not depend on that.

// Floats ordered as integers: neighbours differ by 1, +0 and -0 are both 0.
int64_t OrderedFloat32(uint32_t bits) {
  const int64_t magnitude = bits & 0x7FFFFFFFu;
  return (bits & 0x80000000u) != 0 ? -magnitude : magnitude;
}

int64_t OrderedFloat16(uint32_t bits) {
  const int64_t magnitude = bits & 0x7FFFu;
  return (bits & 0x8000u) != 0 ? -magnitude : magnitude;
}

uint32_t FloatDistance(float a, float b, int64_t orderedA, int64_t orderedB) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b) ? 0 : kIncomparable;
  if (std::isinf(a) || std::isinf(b)) return a == b ? 0 : kIncomparable;
  return static_cast<uint32_t>(std::llabs(orderedA - orderedB));
}

}  // namespace

FormatTolerance Tolerance(DXGI_FORMAT format) {
  switch (KindOf(format, 0)) {
    case ChannelKind::Unorm: return {kUnormSteps, kUnormReason};
    case ChannelKind::Srgb: return {kSrgbSteps, kSrgbReason};
    case ChannelKind::Float16: return {kFloat16Steps, kFloat16Reason};
    case ChannelKind::Float32: return {kFloat32Steps, kFloat32Reason};
    case ChannelKind::Uint: return {kExactSteps, kUintReason};
    case ChannelKind::Absent: break;
  }
  return {kExactSteps, ""};
}

uint32_t StoredDistance(DXGI_FORMAT format, int channel, uint32_t a, uint32_t b) {
  switch (KindOf(format, channel)) {
    case ChannelKind::Absent: return 0;
    case ChannelKind::Unorm:
    case ChannelKind::Srgb:
    case ChannelKind::Uint: return a > b ? a - b : b - a;
    case ChannelKind::Float16:
      return FloatDistance(HalfToFloat(static_cast<uint16_t>(a)), HalfToFloat(static_cast<uint16_t>(b)),
                           OrderedFloat16(a), OrderedFloat16(b));
    case ChannelKind::Float32:
      return FloatDistance(std::bit_cast<float>(a), std::bit_cast<float>(b), OrderedFloat32(a),
                           OrderedFloat32(b));
  }
  return kIncomparable;
}

bool WithinTolerance(DXGI_FORMAT format, const StoredColor& expected, const StoredColor& actual) {
  const FormatTolerance tolerance = Tolerance(format);
  for (int c = 0; c < 4; ++c) {
    const uint32_t distance = StoredDistance(format, c, expected.bits[c], actual.bits[c]);
    if (distance == kIncomparable || distance > tolerance.steps[c]) return false;
  }
  return true;
}

}  // namespace rhi::reference
