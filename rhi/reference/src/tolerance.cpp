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

// float16: an error-propagation bound, not k * unit(m). The FS text it rests on:
//  - FS 17.5 (Blending Precision): for float16 render targets implementations
//    may skip the clamp of the blend inputs, and "blend operations on these
//    formats [must] be done with at least equal precision/range as the output
//    format", up to float32; all OM math "must honor the D3D11 Floating Point
//    Rules (3.1), although operations are considered to be 'fused', and
//    reordering is permitted".
//  - FS 3.2.2 (Floating Point Conversion): "Round-to-zero must be used during
//    conversion to another float format"; beyond the target's range the largest
//    finite value results.
//  - FS 3.1.5 (16-bit Floating Point): unfused float16 operations round to
//    nearest (0.5 ULP); fused ones are within 0.6 ULP.
// So a device may convert each blend input to float16 before it uses it: the
// source colour Cs (float32 from the shader), the blend factor, SV_Target1 and
// each factor's input x; the destination Cd already is a float16. It may then
// form 1 - x, the products C*F and their sum or difference at float16
// precision. NVIDIA does exactly this (docs/conformance_gpu.md: Cs = 10.8984337
// becomes 10.890625, RTZ, and SRC_COLOR squares that).
//
// Per input value x: conv(x) = |x - RTZ16(x)| (exact; 0 when x is a float16,
// which is what also bounds a device that rounds to nearest or does not
// convert). With dx the error of an input and u(y) = float16 ULP at |y|
// (2^(clamp(floor(log2 y), -14, 15) - 10)):
//   direct factors (SRC_COLOR, SRC_ALPHA, DEST_*, BLEND_FACTOR, SRC1_*):
//     dF = conv(x)                                      (DEST_*: 0, already float16)
//   INV_* (1 - x): x is rounded first, then 1 - x' is rounded to float16:
//     dF = conv(x) + u(|1 - x| + conv(x))               (0 when x and 1 - x are float16)
//     For x near 1 the first term is most of F: the rounding of x cancels.
//   SRC_ALPHA_SAT, f = min(As, 1 - Ad): min is 1-Lipschitz in each argument,
//     dF = max(conv(As), error of 1 - Ad as above)      (also for f clamped to [0, 1])
//   ZERO, ONE: dF = 0.
// A product P = C*F computed from C' = C + dC, F' = F + dF:
//     |C'F' - CF| <= |C| dF + |F| dC + dC dF             (dC = conv(Cs); 0 for Cd)
//   rounded to float16 (FS 3.1.5, 0.5 ULP):
//     + 0.5 u(|CF| + that)                              (0 when dC = dF = 0 and CF is a float16)
// The sum / difference r' of the two products: each product's error adds in
// (E = Es + Ed), then one last rounding to float16, either a float16 op (0.5
// ULP, 0.6 fused) or a float32 result converted toward zero (FS 3.2.2, < 1 ULP):
//     device <= Es + Ed + u(|r| + E)   (+ the excess over 65504 where it clamps)
// The reference blends in float32 and stores toward zero: < u(|r|) from the
// float32 result. Float32 roundings, in the reference (1.0f - x, the products,
// the sum) and in a device that blends in float32 in any order (FS 17.5), are
// bounded by s32 = 2^-21 (|Cs|(1 + |Fs|) + |Cd|(1 + |Fd|) + |r|), four
// float32 half-ULPs at each magnitude, invisible at float16 precision.
// Bound = Es + Ed + u(|r| + E + s32) + u(|r| + s32) + s32.
// On the recorded H100 cases it is 1.2-20 float16 ULPs at m = max(|Cs*Fs|,
// |Cd*Fd|, |r|), median 4.9 (large where 1 - x has x near 1, where the device's
// error is large too); the recorded errors are 3-8 ULPs of the result
// (tests/conformance/h100_replay_test.cpp),
// and an error of 16 ULPs, a wrong factor, swapped operands or a wrong op all
// fall outside (tests/reference/tolerance_test.cpp).
constexpr const char* kFloat16TermReason =
    "error propagation at float16 precision: every input may be rounded toward zero to float16 (FS 3.2.2), "
    "1 - x formed from the rounded x, products and sum rounded at float16 (FS 3.1.5, FS 17.5); plus the "
    "reference's round-toward-zero store";

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

double Ulp16(double m) { return UlpAt(m, -14, 15, 10); }

constexpr double kHalfMax = 65504.0;

// x is a float16 value (and so needs no conversion under any rounding).
bool IsHalf(double x) { return std::isfinite(x) && std::fabs(x) <= kHalfMax && Float16ConversionError(x) == 0.0; }

// The error of 1 - x formed at float16 precision from a rounded x.
double InverseError(double x) {
  const double dx = Float16ConversionError(x);
  const double v = 1.0 - x;  // exact in double for a float32 x
  if (dx == 0.0 && IsHalf(v)) return 0.0;
  return dx + Ulp16(std::fabs(v) + dx);
}

// Error of C*F computed from rounded C and F, rounded to float16.
double ProductError(double c, double dc, double f, double df) {
  const double moved = std::fabs(c) * df + std::fabs(f) * dc + dc * df;
  const double p = c * f;
  const double rounding = dc == 0.0 && df == 0.0 && IsHalf(p) ? 0.0 : 0.5 * Ulp16(std::fabs(p) + moved);
  return moved + rounding;
}

}  // namespace

double Float16ConversionError(double x) {
  if (!std::isfinite(x)) return 0.0;
  const float f = static_cast<float>(x);
  const double narrowed = static_cast<double>(f);  // the inputs are float32 values: exact
  const double half = static_cast<double>(HalfToFloat(FloatToHalf(f, HalfRounding::TowardZero)));
  return std::fabs(x - narrowed) + std::fabs(narrowed - half);
}

double Float16FactorError(const FactorSource& source) {
  switch (source.blend) {
    case BLEND_ZERO:
    case BLEND_ONE: return 0.0;
    case BLEND_SRC_COLOR:
    case BLEND_SRC_ALPHA:
    case BLEND_DEST_ALPHA:
    case BLEND_DEST_COLOR:
    case BLEND_BLEND_FACTOR:
    case BLEND_SRC1_COLOR:
    case BLEND_SRC1_ALPHA: return Float16ConversionError(source.input);
    case BLEND_INV_SRC_COLOR:
    case BLEND_INV_SRC_ALPHA:
    case BLEND_INV_DEST_ALPHA:
    case BLEND_INV_DEST_COLOR:
    case BLEND_INV_BLEND_FACTOR:
    case BLEND_INV_SRC1_COLOR:
    case BLEND_INV_SRC1_ALPHA: return InverseError(source.input);
    case BLEND_SRC_ALPHA_SAT:
      return std::max(Float16ConversionError(source.input), InverseError(source.input2));
  }
  return INFINITY;
}

double Float16TermBound(const BlendTerms& terms, int c) {
  if (!terms.arithmetic[c]) return 0.0;
  const double cs = terms.srcOperand[c], cd = terms.destOperand[c];
  const double fs = terms.srcFactor[c], fd = terms.destFactor[c];
  const double r = std::fabs(static_cast<double>(terms.result[c]));
  const double es = ProductError(cs, Float16ConversionError(cs), fs, Float16FactorError(terms.srcFactorSource[c]));
  const double ed = ProductError(cd, Float16ConversionError(cd), fd, Float16FactorError(terms.destFactorSource[c]));
  const double s32 = std::ldexp(std::fabs(cs) * (1.0 + std::fabs(fs)) + std::fabs(cd) * (1.0 + std::fabs(fd)) + r, -21);
  const double reach = r + es + ed + s32;
  const double overflow = std::max(0.0, reach - kHalfMax);  // FS 3.2.2: clamps to 65504
  const double device = es + ed + Ulp16(reach) + overflow;
  const double reference = Ulp16(r + s32);
  return device + reference + s32;
}

TermBound BlendTermK(DXGI_FORMAT format, int channel) {
  switch (KindOf(format, channel)) {
    case ChannelKind::Unorm: return {kUnormTermK, kUnormTermReason};
    case ChannelKind::Srgb: return {kSrgbTermK, kSrgbTermReason};
    case ChannelKind::Float16: return {1.0, kFloat16TermReason, true};
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

// float32 and sRGB targets (float16 has its own bound, Float16TermBound): the
// products are not the only magnitudes that count.
//  - Vulkan only requires blending "with a precision and dynamic range no lower
//    than that used to represent destination components" and leaves the
//    evaluation order open: llvmpipe evaluates OVER-like blends as
//    Cd + Fs*(Cs - Cd).
//  - FS 17.5 lets the blender work at the render target's precision, so the
//    source colour and the factors derived from it may be rounded to the
//    target format before the products (NVIDIA does so on sRGB targets).
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

BlendVerdict CompareReading(DXGI_FORMAT format, const BlendReading& expected, const StoredColor& actual) {
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
      v.m = kind == ChannelKind::Unorm || kind == ChannelKind::Float16 ? TermMagnitude(expected.terms, c)
                                                                       : OperandMagnitude(expected.terms, c);
      v.unit = BlendUnit(format, c, v.m);
      v.bound = tb.propagated ? tb.k * Float16TermBound(expected.terms, c) : tb.k * v.unit;
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

BlendVerdict CompareBlend(DXGI_FORMAT format, const BlendOutput& expected, const StoredColor& actual) {
  const BlendVerdict formula = CompareReading(format, expected, actual);
  if (formula.ok || !expected.hasSaturatedReading) return formula;
  BlendVerdict saturated = CompareReading(format, expected.saturated, actual);
  if (!saturated.ok) return formula;  // report against the FS 17.1 formula
  saturated.usedSaturatedReading = true;
  return saturated;
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
