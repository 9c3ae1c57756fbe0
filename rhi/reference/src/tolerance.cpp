#include "rhi_reference/tolerance.h"

#include <algorithm>
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

// Note for every tolerance above: it holds when the blend does not cancel.
// SUBTRACT / REV_SUBTRACT of nearly equal terms (or ADD of terms of opposite
// sign) leaves the absolute error of the terms on a small result, many ULPs of
// it. That case is covered by the term bound below, not by these tables.

// ---------------------------------------------------------------------------
// The blend-term bound: |gpu - ref| <= k * unit(m), m = max(|Cs*Fs|, |Cd*Fd|, |r|),
// in linear float space, for ADD / SUBTRACT / REV_SUBTRACT only.
//
// Why the operands and not the result: FS 17.5 lets the blender run "at equal
// or more precision than the output format", i.e. it may round Cs*Fs and Cd*Fd
// to the RT's precision before the op. Those roundings are ½ unit at the
// magnitude of each product. When the op cancels, the result is small but its
// absolute error is still that of the products; a bound relative to the result
// (the tables above) cannot hold. Everything below is in units at m; since
// every product and the result are <= m in magnitude and every unit used is
// non-decreasing in magnitude, each rounding is at most ½ unit(m).
// Factors such as 1 - a are computed the same way (float32) by the reference
// and any device, so their rounding is common to both and not counted.
//
// UNORM: unit = 1/(2^bits - 1), independent of m. Device: two product roundings
// at the RT precision (FS 17.5, ½ + ½) + float->UNORM (FS 3.2.3.6, 0.6); the
// reference's own store ½: 2.1 steps. A distance between two UNORM values is a
// whole number of steps, so k = 2. Unblended writes and MIN/MAX keep 1 (table).
constexpr double kUnormTermK = 2.0;
constexpr const char* kUnormTermReason =
    "2 steps for ADD/SUBTRACT/REV_SUBTRACT: two product roundings at the RT precision (FS 17.5) + "
    "float->UNORM 0.6 (FS 3.2.3.6) + reference 0.5 = 2.1";

// sRGB colour: the blend happens in linear space (FS 17.4), so the error is
// judged there. unit(m) = the linear width of the 8-bit sRGB step that contains
// linear m: SrgbToLinear((c+1)/255) - SrgbToLinear(c/255), c = floor(255*
// LinearToSrgb(min(m,1))), c <= 254. The width grows with m (the decode curve
// is convex), so every error below, made at a magnitude <= m, is <= its number
// of half-steps times unit(m):
//   destination decode (FS 3.2.3.7) ½ sRGB step at |Cd|, scaled by Fd <= 1:
//     the linear step width grows like x^0.58 (slope of the decode; constant on
//     the linear segment), so Fd * step(|Cd|) <= step(|Cd*Fd|) <= unit(m): 0.5;
//   two product roundings at the RT precision (FS 17.5): 0.5 + 0.5;
//   float->sRGB encode of the result (FS 3.2.3.8): 0.6 of the step at |r|;
//   the reference's own store: 0.5.
// Total k = 2.6. Linear differences are not whole steps, so no rounding down.
// Not "max(sRGB step, one UNORM8 step in linear)": below linear ~0.27 the UNORM8
// step is wider than the sRGB step (12.9x near black), and the FS gives the
// blender the precision of the RT format, which is the sRGB step; taking the
// UNORM8 step would admit tens of codes near black with no FS basis.
// Alpha is stored linear (FS 19.1.3.2): the UNORM rule.
constexpr double kSrgbTermK = 2.6;
constexpr const char* kSrgbTermReason =
    "2.6 linear-space sRGB steps at m: dest decode 0.5 (FS 3.2.3.7) + two product roundings (FS 17.5) "
    "+ encode 0.6 (FS 3.2.3.8) + reference 0.5";

// float32: unit = ULP(m) = 2^(floor(log2 m) - 23) (FS 3.1.3; m below 2^-126 uses
// 2^-149, denorms flush). Reference: Cs*Fs, Cd*Fd, op, each rounded to nearest
// (½ ULP at its own magnitude). All three cannot sit in m's binade: ADD of like
// signs puts r in the binade above the products, a difference of two values of
// one binade lies below it. So <= ½(1 + 1 + ½) = 1.25 ULP(m). A device that
// evaluates the same expression, fused or in another order of those three
// operations (FS 17.5), is bounded the same: 1.25. k = 2.5.
constexpr double kFloat32TermK = 2.5;
constexpr const char* kFloat32TermReason =
    "2.5 float32 ULPs at m: reference and device each <= 1.25 ULP(m) (three roundings, FS 3.1.3, FS 17.5)";

// float16: unit = float16 ULP(m) = 2^(clamp(floor(log2 m), -14, 15) - 10).
// Device blending at float16 precision (FS 17.5), round to nearest: 1.25 ULP(m)
// by the argument above; blending in float32 and storing toward zero (FS 3.2.2):
// < 1 ULP(m). Reference: float32 then toward zero, < 1 ULP(m). k = 2.25.
constexpr double kFloat16TermK = 2.25;
constexpr const char* kFloat16TermReason =
    "2.25 float16 ULPs at m: device <= 1.25 ULP(m) at float16 precision (FS 17.5) + reference "
    "round-toward-zero store < 1 (FS 3.2.2)";

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

double UlpAt(double m, int minExponent, int maxExponent, int mantissaBits) {
  if (!std::isfinite(m)) return INFINITY;
  const int e = m > 0 ? std::clamp(std::ilogb(m), minExponent, maxExponent) : minExponent;
  return std::ldexp(1.0, e - mantissaBits);
}

}  // namespace

TermBound BlendTermK(DXGI_FORMAT format, int channel) {
  switch (KindOf(format, channel)) {
    case ChannelKind::Unorm: return {kUnormTermK, kUnormTermReason};
    case ChannelKind::Srgb: return {kSrgbTermK, kSrgbTermReason};
    case ChannelKind::Float16: return {kFloat16TermK, kFloat16TermReason};
    case ChannelKind::Float32: return {kFloat32TermK, kFloat32TermReason};
    case ChannelKind::Uint:
    case ChannelKind::Absent: break;
  }
  return {0.0, "no term bound: exact or absent"};
}

double TermMagnitude(const BlendTerms& terms, int channel) {
  if (!terms.arithmetic[channel]) return 0.0;
  return std::max({std::fabs(static_cast<double>(terms.srcTerm[channel])),
                   std::fabs(static_cast<double>(terms.destTerm[channel])),
                   std::fabs(static_cast<double>(terms.result[channel]))});
}

// Float and sRGB targets: the products are not the only magnitudes that count.
//  - Vulkan only requires blending "with a precision and dynamic range no lower
//    than that used to represent destination components" and leaves the
//    evaluation order open: llvmpipe evaluates OVER-like blends as
//    Cd + Fs*(Cs - Cd).
//  - FS 17.5 lets the blender work at the render target's precision, so the
//    source colour and the factors derived from it may be rounded to the
//    target format before the products (NVIDIA does so on float16 and sRGB
//    targets: 1 - As with As rounded to float16 first).
// Either way the error is one RT unit at the operands' magnitude, not at the
// products': the bound uses max(m, |Cs| + |Cd|, |Cs*Fs| + |Cd*Fd| + |Cd|), the
// largest value any such evaluation handles. UNORM units are absolute and
// need no such widening. docs/conformance.md counts the cases that need it.
double OperandMagnitude(const BlendTerms& terms, int channel) {
  const double s = std::fabs(static_cast<double>(terms.srcOperand[channel]));
  const double d = std::fabs(static_cast<double>(terms.destOperand[channel]));
  const double sTerm = std::fabs(static_cast<double>(terms.srcTerm[channel]));
  const double dTerm = std::fabs(static_cast<double>(terms.destTerm[channel]));
  return std::max({TermMagnitude(terms, channel), s + d, sTerm + dTerm + d});
}

double BlendUnit(DXGI_FORMAT format, int channel, double m) {
  switch (KindOf(format, channel)) {
    case ChannelKind::Unorm: return 1.0 / static_cast<double>((1u << UnormBits(format, channel)) - 1u);
    case ChannelKind::Srgb: {
      const double encoded = LinearToSrgb(static_cast<float>(std::min(std::max(m, 0.0), 1.0)));
      const int c = std::clamp(static_cast<int>(std::floor(encoded * 255.0)), 0, 254);
      return static_cast<double>(SrgbToLinear((c + 1) / 255.0f)) - static_cast<double>(SrgbToLinear(c / 255.0f));
    }
    case ChannelKind::Float16: return UlpAt(m, -14, 15, 10);
    case ChannelKind::Float32: return UlpAt(m, -126, 127, 23);
    case ChannelKind::Uint:
    case ChannelKind::Absent: break;
  }
  return 0.0;
}

BlendVerdict CompareBlend(DXGI_FORMAT format, const BlendOutput& expected, const StoredColor& actual) {
  BlendVerdict verdict;
  const FormatTolerance table = Tolerance(format);
  const Float4 gpu = Decode(format, actual);
  for (int c = 0; c < 4; ++c) {
    ChannelVerdict& v = verdict.channels[c];
    const ChannelKind kind = KindOf(format, c);
    if (kind == ChannelKind::Absent) continue;
    v.steps = StoredDistance(format, c, expected.stored.bits[c], actual.bits[c]);
    v.withinTable = v.steps != kIncomparable && v.steps <= table.steps[c];
    const TermBound tb = BlendTermK(format, c);
    v.termBoundApplies = expected.terms.arithmetic[c] && tb.k > 0 && v.steps != kIncomparable;
    if (v.termBoundApplies) {
      v.m = kind == ChannelKind::Unorm ? TermMagnitude(expected.terms, c) : OperandMagnitude(expected.terms, c);
      v.unit = BlendUnit(format, c, v.m);
      v.bound = tb.k * v.unit;
      // UNORM values are whole steps apart: compare the exact step count, not
      // the difference of two rounded decodes.
      v.error = kind == ChannelKind::Unorm
                    ? v.steps * v.unit
                    : std::fabs(static_cast<double>(gpu[c]) - static_cast<double>(expected.decoded[c]));
      v.withinTermBound = kind == ChannelKind::Unorm ? v.steps <= static_cast<uint32_t>(tb.k)
                                                     : std::isfinite(v.error) && v.error <= v.bound;
    }
    verdict.ok = verdict.ok && v.ok();
    verdict.usedTermBound = verdict.usedTermBound || v.NeededTermBound();
  }
  return verdict;
}

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
