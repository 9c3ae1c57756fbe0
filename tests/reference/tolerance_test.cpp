// The tolerance table and the stored-value comparison.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>

#include "rhi_reference/blend.h"
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


// ---------------------------------------------------------------------------
// The blend-term bound: |gpu - ref| <= k * unit(m), m = max(|Cs*Fs|, |Cd*Fd|, |r|),
// ADD / SUBTRACT / REV_SUBTRACT only.

RENDER_TARGET_BLEND_DESC Blend(BLEND src, BLEND dest, BLEND_OP op) {
  RENDER_TARGET_BLEND_DESC b;
  b.BlendEnable = TRUE;
  b.SrcBlend = src;
  b.DestBlend = dest;
  b.BlendOp = op;
  b.SrcBlendAlpha = BLEND_ONE;
  b.DestBlendAlpha = BLEND_ZERO;
  b.BlendOpAlpha = BLEND_OP_ADD;
  return b;
}

constexpr Float4 kOnes{1, 1, 1, 1};

TEST(TermBound, KAndUnits) {
  EXPECT_EQ(BlendTermK(DXGI_FORMAT_R8G8B8A8_UNORM, 0).k, 2.0);
  EXPECT_EQ(BlendTermK(DXGI_FORMAT_R8G8B8A8_UNORM_SRGB, 0).k, 2.6);
  EXPECT_EQ(BlendTermK(DXGI_FORMAT_R8G8B8A8_UNORM_SRGB, 3).k, 2.0);  // alpha is linear UNORM
  EXPECT_TRUE(BlendTermK(DXGI_FORMAT_R16_FLOAT, 0).propagated);  // Float16TermBound
  EXPECT_FALSE(BlendTermK(DXGI_FORMAT_R32_FLOAT, 0).propagated);
  EXPECT_EQ(BlendTermK(DXGI_FORMAT_R32_FLOAT, 0).k, 2.5);
  EXPECT_EQ(BlendTermK(DXGI_FORMAT_R32_UINT, 0).k, 0.0);
  EXPECT_EQ(BlendTermK(DXGI_FORMAT_R32_FLOAT, 1).k, 0.0);  // absent channel
  EXPECT_NE(std::string(BlendTermK(DXGI_FORMAT_R8_UNORM, 0).reason).find("17.5"), std::string::npos);

  EXPECT_DOUBLE_EQ(BlendUnit(DXGI_FORMAT_R8_UNORM, 0, 0.7), 1.0 / 255.0);
  EXPECT_DOUBLE_EQ(BlendUnit(DXGI_FORMAT_R10G10B10A2_UNORM, 3, 0.7), 1.0 / 3.0);
  EXPECT_EQ(BlendUnit(DXGI_FORMAT_R32_FLOAT, 0, 1.5), std::ldexp(1.0, -23));
  EXPECT_EQ(BlendUnit(DXGI_FORMAT_R32_FLOAT, 0, 34.5), std::ldexp(1.0, -18));
  EXPECT_EQ(BlendUnit(DXGI_FORMAT_R32_FLOAT, 0, 0.0), std::ldexp(1.0, -149));
  EXPECT_EQ(BlendUnit(DXGI_FORMAT_R16_FLOAT, 0, 1.5), std::ldexp(1.0, -10));
  EXPECT_EQ(BlendUnit(DXGI_FORMAT_R16_FLOAT, 0, 0.0), std::ldexp(1.0, -24));
  // sRGB near black: the linear segment, one code = 1 / (255 * 12.92) in linear.
  EXPECT_NEAR(BlendUnit(DXGI_FORMAT_R8G8B8A8_UNORM_SRGB, 0, 0.001), 1.0 / (255.0 * 12.92), 1e-7);
  // sRGB steps widen with m (the decode is convex), and exceed a UNORM8 step near white.
  EXPECT_LT(BlendUnit(DXGI_FORMAT_R8G8B8A8_UNORM_SRGB, 0, 0.05), BlendUnit(DXGI_FORMAT_R8G8B8A8_UNORM_SRGB, 0, 0.5));
  EXPECT_GT(BlendUnit(DXGI_FORMAT_R8G8B8A8_UNORM_SRGB, 0, 1.0), 1.0 / 255.0);
}

TEST(TermBound, ReferenceReportsTheTerms) {
  // SUBTRACT: terms recorded, m = the larger product.
  const BlendOutput sub = BlendResult(DXGI_FORMAT_R32G32B32A32_FLOAT, Blend(BLEND_SRC_ALPHA, BLEND_ONE, BLEND_OP_SUBTRACT),
                                      kOnes, Float4{0.75f, 2.0f, -4.0f, 0.5f}, {},
                                      Encode(DXGI_FORMAT_R32G32B32A32_FLOAT, Float4{0.25f, 1.0f, -1.5f, 0.0f}));
  EXPECT_EQ(sub.terms.srcTerm[0], 0.375f);
  EXPECT_EQ(sub.terms.destTerm[0], 0.25f);
  EXPECT_EQ(sub.terms.result[0], 0.125f);
  EXPECT_TRUE(sub.terms.arithmetic[0]);
  EXPECT_EQ(TermMagnitude(sub.terms, 0), 0.375);
  EXPECT_EQ(TermMagnitude(sub.terms, 2), 2.0);  // -4*0.5 - (-1.5) = -0.5: |src term| 2 is the largest
  // MIN / MAX, unblended writes and masked channels carry no arithmetic.
  const BlendOutput min = BlendResult(DXGI_FORMAT_R32_FLOAT, Blend(BLEND_ONE, BLEND_ONE, BLEND_OP_MIN), kOnes,
                                      Float4{3, 0, 0, 0}, {}, StoredColor{});
  EXPECT_FALSE(min.terms.arithmetic[0]);
  EXPECT_EQ(TermMagnitude(min.terms, 0), 0.0);
  RENDER_TARGET_BLEND_DESC off = Blend(BLEND_ONE, BLEND_ONE, BLEND_OP_ADD);
  off.BlendEnable = FALSE;
  EXPECT_FALSE(BlendResult(DXGI_FORMAT_R32_FLOAT, off, kOnes, Float4{3, 0, 0, 0}, {}, StoredColor{}).terms.arithmetic[0]);
  RENDER_TARGET_BLEND_DESC masked = Blend(BLEND_ONE, BLEND_ONE, BLEND_OP_ADD);
  masked.RenderTargetWriteMask = COLOR_WRITE_ENABLE_GREEN;
  const BlendOutput m = BlendResult(DXGI_FORMAT_R8G8B8A8_UNORM, masked, kOnes, Float4{0.5f, 0.5f, 0, 0}, {}, StoredColor{});
  EXPECT_FALSE(m.terms.arithmetic[0]);
  EXPECT_TRUE(m.terms.arithmetic[1]);
  // UINT targets are never blended.
  EXPECT_FALSE(BlendResult(DXGI_FORMAT_R32_UINT, Blend(BLEND_ONE, BLEND_ONE, BLEND_OP_ADD), kOnes,
                           UintRegister(1, 0, 0, 0), {}, StoredColor{})
                   .terms.arithmetic[0]);
}

StoredColor WithChannel(StoredColor c, int channel, uint32_t bits) {
  c.bits[channel] = bits;
  return c;
}

TEST(TermBound, UnormCancellation) {
  // The lavapipe case: SRC_COLOR/INV_SRC_COLOR/SUBTRACT on blue, src 0.571,
  // dest 0xc1: 0.571^2 - 0.757*0.429 ~ 0.0013 -> code 0. 2 codes off is inside
  // (two product roundings, FS 17.5), 3 is outside.
  constexpr DXGI_FORMAT kFmt = DXGI_FORMAT_R8G8B8A8_UNORM;
  const RENDER_TARGET_BLEND_DESC b = Blend(BLEND_SRC_COLOR, BLEND_INV_SRC_COLOR, BLEND_OP_SUBTRACT);
  const BlendOutput ref = BlendResult(kFmt, b, kOnes, Float4{0.2f, 0.2f, 0.571f, 1.0f}, {},
                                      StoredColor{{0x33, 0x33, 0xc1, 0xff}});
  ASSERT_EQ(ref.stored.bits[2], 0u);
  const BlendVerdict two = CompareBlend(kFmt, ref, WithChannel(ref.stored, 2, 2));
  EXPECT_TRUE(two.ok);
  EXPECT_TRUE(two.usedTermBound);
  EXPECT_FALSE(two.channels[2].withinTable);
  EXPECT_FALSE(CompareBlend(kFmt, ref, WithChannel(ref.stored, 2, 3)).ok);
  // 1 code needs no allowance.
  const BlendVerdict one = CompareBlend(kFmt, ref, WithChannel(ref.stored, 2, 1));
  EXPECT_TRUE(one.ok);
  EXPECT_FALSE(one.usedTermBound);
}

TEST(TermBound, UnormMinMaxAndUnblendedKeepOneStep) {
  constexpr DXGI_FORMAT kFmt = DXGI_FORMAT_R8_UNORM;
  const BlendOutput min = BlendResult(kFmt, Blend(BLEND_ONE, BLEND_ONE, BLEND_OP_MIN), kOnes,
                                      Float4{0.5f, 0, 0, 0}, {}, StoredColor{{200, 0, 0, 0}});
  EXPECT_TRUE(CompareBlend(kFmt, min, WithChannel(min.stored, 0, min.stored.bits[0] + 1)).ok);
  EXPECT_FALSE(CompareBlend(kFmt, min, WithChannel(min.stored, 0, min.stored.bits[0] + 2)).ok);
  RENDER_TARGET_BLEND_DESC off = Blend(BLEND_ONE, BLEND_ONE, BLEND_OP_ADD);
  off.BlendEnable = FALSE;
  const BlendOutput plain = BlendResult(kFmt, off, kOnes, Float4{0.5f, 0, 0, 0}, {}, StoredColor{});
  EXPECT_FALSE(CompareBlend(kFmt, plain, WithChannel(plain.stored, 0, plain.stored.bits[0] + 2)).ok);
}

TEST(TermBound, SrgbCancellationJudgedInLinearSpace) {
  // The lavapipe case: INV_SRC_ALPHA/BLEND_FACTOR/SUBTRACT on green, src 0.6797
  // (alpha clamps to 0, so Fs = 1), dest code 0xd7, blend factor clamps to 1:
  // 0.6797 - 0.6795 -> sRGB code 1. The device wrote 4: 3 codes near black but
  // 0.0012 in linear, against 2.6 sRGB steps at the operands' magnitude
  // m = |Cs*Fs| + |Cd*Fd| + |Cd| = 0.6797 + 0.6795 + 0.6795: inside.
  constexpr DXGI_FORMAT kFmt = DXGI_FORMAT_R8G8B8A8_UNORM_SRGB;
  const RENDER_TARGET_BLEND_DESC b = Blend(BLEND_INV_SRC_ALPHA, BLEND_BLEND_FACTOR, BLEND_OP_SUBTRACT);
  const Float4 factor{1.09645271f, 1.45093727f, 1.23960161f, 0.684657693f};
  const Float4 src{-0.00570496917f, 0.679705381f, 0.63694489f, -0.235142946f};
  const BlendOutput ref = BlendResult(kFmt, b, factor, src, {}, StoredColor{{0xe2, 0xd7, 0xfd, 0xb3}});
  ASSERT_EQ(ref.stored.bits[1], 1u);
  const BlendVerdict four = CompareBlend(kFmt, ref, WithChannel(ref.stored, 1, 4));
  EXPECT_TRUE(four.ok);
  EXPECT_TRUE(four.usedTermBound);
  EXPECT_NEAR(four.channels[1].m, 0.6797 + 2 * 0.6795, 2e-3);
  // Just outside: the first code whose linear distance exceeds 2.6 steps at m.
  const double bound = four.channels[1].bound;
  uint32_t firstOut = 2;
  while (SrgbToLinear(firstOut / 255.0f) - ref.decoded[1] <= bound) ++firstOut;
  EXPECT_GT(firstOut, 30u);  // the bound is tens of codes near black at this m
  EXPECT_TRUE(CompareBlend(kFmt, ref, WithChannel(ref.stored, 1, firstOut - 1)).ok);
  const BlendVerdict out = CompareBlend(kFmt, ref, WithChannel(ref.stored, 1, firstOut));
  EXPECT_FALSE(out.ok);
  EXPECT_GT(out.channels[1].error, out.channels[1].bound);
}

TEST(TermBound, SrgbSmallOperandsStayTight) {
  // No large operand: dest code 5 (linear segment) + 0. m ~ 0.0015, one sRGB
  // step = 1/(255*12.92): 2 codes are within the table, 3 codes (0.9e-3 > 2.6
  // steps) are outside; a UNORM8-step floor would have let ~30 codes through.
  constexpr DXGI_FORMAT kFmt = DXGI_FORMAT_R8G8B8A8_UNORM_SRGB;
  const BlendOutput ref = BlendResult(kFmt, Blend(BLEND_ONE, BLEND_ONE, BLEND_OP_ADD), kOnes, Float4{0, 0, 0, 0}, {},
                                      StoredColor{{5, 5, 5, 0}});
  ASSERT_EQ(ref.stored.bits[0], 5u);
  EXPECT_TRUE(CompareBlend(kFmt, ref, WithChannel(ref.stored, 0, 7)).ok);
  EXPECT_FALSE(CompareBlend(kFmt, ref, WithChannel(ref.stored, 0, 8)).ok);
}

TEST(TermBound, Float32Cancellation) {
  // ONE/ONE/SUBTRACT of (1 + 2^-23) and 1: exact result 2^-23. For float32 the
  // magnitude also covers rearranged evaluation orders (Vulkan leaves the order
  // open): M = |Cs*Fs| + |Cd*Fd| + |Cd| = 3 + 2^-23, ULP(M) = 2^-22, bound
  // 2.5 * 2^-22 = 5 * 2^-23. 4 * 2^-23 (3 ULP of 2^-23 away) is inside, 7 * 2^-23
  // (6 away) and -5 * 2^-23 (6 away) are outside.
  constexpr DXGI_FORMAT kFmt = DXGI_FORMAT_R32_FLOAT;
  const float ulp = std::ldexp(1.0f, -23);
  const BlendOutput ref = BlendResult(kFmt, Blend(BLEND_ONE, BLEND_ONE, BLEND_OP_SUBTRACT), kOnes,
                                      Float4{1.0f + ulp, 0, 0, 0}, {}, Encode(kFmt, Float4{1.0f, 0, 0, 0}));
  ASSERT_EQ(ref.decoded[0], ulp);
  const BlendVerdict in = CompareBlend(kFmt, ref, Encode(kFmt, Float4{4 * ulp, 0, 0, 0}));
  EXPECT_TRUE(in.ok);
  EXPECT_TRUE(in.usedTermBound);
  EXPECT_GT(in.channels[0].steps, 1000000u);
  EXPECT_FALSE(CompareBlend(kFmt, ref, Encode(kFmt, Float4{7 * ulp, 0, 0, 0})).ok);
  EXPECT_FALSE(CompareBlend(kFmt, ref, Encode(kFmt, Float4{-5 * ulp, 0, 0, 0})).ok);
  // NaN / INF are never inside.
  EXPECT_FALSE(CompareBlend(kFmt, ref, Encode(kFmt, Float4{INFINITY, 0, 0, 0})).ok);
  EXPECT_FALSE(CompareBlend(kFmt, ref, Encode(kFmt, Float4{NAN, 0, 0, 0})).ok);
}

TEST(TermBound, Float32RearrangedEvaluationIsBoundedByTheOperands) {
  // ZERO/ONE/ADD: the source is multiplied by 0, so D3D11's exact form gives the
  // destination. llvmpipe evaluates Cd + Fs*(Cs - Cd), which lets the large
  // source's rounding in: the bound for float32 uses M = |Cs| + |Cd| = 34.728,
  // ULP(M) = 2^-18, bound 2.5 * 2^-18. Half an ULP of the source (2^-19) is
  // inside; 3 * 2^-18 is outside. TermMagnitude (the D3D11 products) stays |Cd|.
  constexpr DXGI_FORMAT kFmt = DXGI_FORMAT_R32_FLOAT;
  const BlendOutput ref = BlendResult(kFmt, Blend(BLEND_ZERO, BLEND_ONE, BLEND_OP_ADD), kOnes,
                                      Float4{-34.5f, 0, 0, 0}, {}, Encode(kFmt, Float4{-0.228f, 0, 0, 0}));
  EXPECT_EQ(TermMagnitude(ref.terms, 0), std::fabs(-0.228f));
  EXPECT_TRUE(CompareBlend(kFmt, ref, Encode(kFmt, Float4{-0.228f + std::ldexp(1.0f, -19), 0, 0, 0})).ok);
  EXPECT_FALSE(CompareBlend(kFmt, ref, Encode(kFmt, Float4{-0.228f + 3 * std::ldexp(1.0f, -18), 0, 0, 0})).ok);
}

TEST(TermBound, Float32MinIsNotWidened) {
  constexpr DXGI_FORMAT kFmt = DXGI_FORMAT_R32_FLOAT;
  const BlendOutput ref = BlendResult(kFmt, Blend(BLEND_ONE, BLEND_ONE, BLEND_OP_MIN), kOnes, Float4{1.0f, 0, 0, 0},
                                      {}, Encode(kFmt, Float4{2.0f, 0, 0, 0}));
  EXPECT_TRUE(CompareBlend(kFmt, ref, StoredColor{{0x3F800002u, 0, 0, 0}}).ok);
  EXPECT_FALSE(CompareBlend(kFmt, ref, StoredColor{{0x3F800003u, 0, 0, 0}}).ok);
}

TEST(TermBound, Float16CancellationOfExactInputs) {
  // ONE/ONE/SUBTRACT of (1 + 2^-10) and 1 in float16: every input is a float16
  // value and the factors are exact, so no rounding happens before the op, and
  // 1 + 2^-10 - 1 is exact: the bound is the two final roundings at 2^-10
  // (device and reference, 2^-20 each) plus the float32 slack
  // 2^-21 * (|Cs|*2 + |Cd|*2 + |r|) = 2^-21 * (4 + 3 * 2^-10):
  // 4 * 2^-10 is far outside; 2 stored steps pass by the table.
  constexpr DXGI_FORMAT kFmt = DXGI_FORMAT_R16_FLOAT;
  const float ulp = std::ldexp(1.0f, -10);
  const BlendOutput ref = BlendResult(kFmt, Blend(BLEND_ONE, BLEND_ONE, BLEND_OP_SUBTRACT), kOnes,
                                      Float4{1.0f + ulp, 0, 0, 0}, {}, Encode(kFmt, Float4{1.0f, 0, 0, 0}));
  ASSERT_EQ(ref.decoded[0], ulp);
  const BlendVerdict exact = CompareBlend(kFmt, ref, ref.stored);
  EXPECT_NEAR(exact.channels[0].bound, 2 * std::ldexp(1.0, -20) + std::ldexp(4.0 + 3 * ulp, -21), 1e-15);
  EXPECT_FALSE(CompareBlend(kFmt, ref, Encode(kFmt, Float4{4 * ulp, 0, 0, 0})).ok);
  EXPECT_TRUE(CompareBlend(kFmt, ref, StoredColor{{ref.stored.bits[0] + 2, 0, 0, 0}}).ok);  // table
}

TEST(TermBound, Float16CancellationOfRoundedInputs) {
  // The same SUBTRACT with a source that is not a float16 value: 1 + 1.5 * 2^-10
  // converts toward zero to 1 + 2^-10 (conv = 2^-11), so a device that rounds
  // its inputs first (FS 17.5, FS 3.2.2) returns 2^-10 where the exact result
  // is 1.5 * 2^-10: the bound holds that, not a 3 * 2^-10 error.
  constexpr DXGI_FORMAT kFmt = DXGI_FORMAT_R16_FLOAT;
  const float ulp = std::ldexp(1.0f, -10);
  const BlendOutput ref = BlendResult(kFmt, Blend(BLEND_ONE, BLEND_ONE, BLEND_OP_SUBTRACT), kOnes,
                                      Float4{1.0f + 1.5f * ulp, 0, 0, 0}, {}, Encode(kFmt, Float4{1.0f, 0, 0, 0}));
  ASSERT_EQ(ref.decoded[0], 1.5f * ulp);
  EXPECT_TRUE(CompareBlend(kFmt, ref, Encode(kFmt, Float4{ulp, 0, 0, 0})).ok);
  EXPECT_TRUE(CompareBlend(kFmt, ref, Encode(kFmt, Float4{2 * ulp, 0, 0, 0})).ok);
  EXPECT_FALSE(CompareBlend(kFmt, ref, Encode(kFmt, Float4{4.5f * ulp, 0, 0, 0})).ok);
}

TEST(Float16Bound, ConversionAndFactorErrors) {
  // conv(x) = |x - RTZ16(x)|: 0 for float16 values, below one ULP otherwise.
  EXPECT_EQ(Float16ConversionError(1.0), 0.0);
  EXPECT_EQ(Float16ConversionError(-2.5), 0.0);
  const float third = 1.0f / 3.0f;
  EXPECT_DOUBLE_EQ(Float16ConversionError(third), static_cast<double>(third) - 0.333251953125);  // 0x3555
  EXPECT_NEAR(Float16ConversionError(10.8984337f), 10.8984337f - 10.890625, 1e-9);  // the H100's RTZ
  EXPECT_EQ(Float16ConversionError(70000.0), 70000.0 - 65504.0);                   // FS 3.2.2 clamp
  // Factors.
  EXPECT_EQ(Float16FactorError({BLEND_ONE, 5.3f, 0}), 0.0);
  EXPECT_EQ(Float16FactorError({BLEND_ZERO, 5.3f, 0}), 0.0);
  EXPECT_EQ(Float16FactorError({BLEND_DEST_ALPHA, 0.75f, 0}), 0.0);
  EXPECT_NEAR(Float16FactorError({BLEND_SRC_ALPHA, 10.8984337f, 0}), 10.8984337f - 10.890625, 1e-9);
  // 1 - x with x and 1 - x float16 values: exact.
  EXPECT_EQ(Float16FactorError({BLEND_INV_SRC_ALPHA, 0.25f, 0}), 0.0);
  // 1 - x with x rounded first: conv(x) + one ULP of 1 - x.
  const float x = 0.999f;
  EXPECT_NEAR(Float16FactorError({BLEND_INV_SRC_ALPHA, x, 0}),
              Float16ConversionError(x) + std::ldexp(1.0, -20), 1e-12);  // 1 - x ~ 0.001: ULP 2^-20
  // SRC_ALPHA_SAT: the larger of its two inputs' errors.
  EXPECT_EQ(Float16FactorError({BLEND_SRC_ALPHA_SAT, 0.5f, 0.25f}), 0.0);
  EXPECT_NEAR(Float16FactorError({BLEND_SRC_ALPHA_SAT, 10.8984337f, 0.25f}), 10.8984337f - 10.890625, 1e-9);
  // SRC_ALPHA_SAT's alpha factor is the constant 1: no error.
  RENDER_TARGET_BLEND_DESC sat = Blend(BLEND_ONE, BLEND_ZERO, BLEND_OP_ADD);
  sat.SrcBlendAlpha = BLEND_SRC_ALPHA_SAT;
  const BlendOutput satOut = BlendResult(DXGI_FORMAT_R16G16B16A16_FLOAT, sat, kOnes, Float4{1, 1, 1, 10.8984337f}, {},
                                         StoredColor{});
  EXPECT_EQ(Float16FactorError(satOut.terms.srcFactorSource[3]), 0.0);
  EXPECT_EQ(satOut.terms.srcFactor[3], 1.0f);
}

// The first recorded H100 case (docs/conformance_gpu.md): R16G16B16A16_FLOAT,
// RGB SRC_COLOR/INV_SRC1_COLOR/ADD, src0.r = 10.8984337, src1.r = 0, dest.r =
// 0x3dbc (1.43359375). D3D11's value: 10.8984337^2 + 1.43359375 = 120.21...
// -> 0x5783 (120.1875, toward zero). The H100 rounds src0 toward zero to
// 10.890625 (FS 3.2.2), squares it (118.606) and stores 120.0 = 0x5780: 3 ULPs
// (0.0625 each) off, 0.1875 absolute; the old 2.25 ULP(m) bound was 0.141.
struct H100Case {
  DXGI_FORMAT format = DXGI_FORMAT_R16G16B16A16_FLOAT;
  RENDER_TARGET_BLEND_DESC blend = [] {
    RENDER_TARGET_BLEND_DESC b = Blend(BLEND_SRC_COLOR, BLEND_INV_SRC1_COLOR, BLEND_OP_ADD);
    b.SrcBlendAlpha = BLEND_INV_SRC_ALPHA;
    b.DestBlendAlpha = BLEND_BLEND_FACTOR;
    b.BlendOpAlpha = BLEND_OP_MAX;
    return b;
  }();
  Float4 src0{10.8984337f, -18.7486877f, -1.42377734f, 0.52737236f};
  Float4 src1{0.0f, 0.269391775f, -1.67019939f, 0.610658169f};
  Float4 factor{-1.83523095f, -0.637968302f, 1.15725684f, -1.27505267f};
  StoredColor dest{{0x3dbc, 0x41cd, 0x4144, 0x3898}};
  StoredColor actual{{0x5780, 0x5d84, 0x4887, 0x3898}};
  BlendOutput Ref(const RENDER_TARGET_BLEND_DESC& b) const { return BlendResult(format, b, factor, src0, src1, dest); }
};

TEST(Float16Bound, AcceptsTheH100) {
  const H100Case c;
  const BlendOutput ref = c.Ref(c.blend);
  ASSERT_EQ(ref.stored, (StoredColor{{0x5783, 0x5d86, 0x4887, 0x3898}}));
  const BlendVerdict v = CompareBlend(c.format, ref, c.actual);
  EXPECT_TRUE(v.ok);
  EXPECT_TRUE(v.usedTermBound);
  EXPECT_FALSE(v.channels[0].withinTable);
  EXPECT_NEAR(v.channels[0].error, 0.1875, 1e-9);
  // The bound is a few ULPs (0.0625 at 64..128) of the blend: about 4 here.
  EXPECT_GT(v.channels[0].bound, 0.1875);
  EXPECT_LT(v.channels[0].bound, 6 * 0.0625);
}

StoredColor Moved(StoredColor c, int channel, int steps) {
  // float16 ordered move (positive values here).
  c.bits[channel] = static_cast<uint32_t>(static_cast<int>(c.bits[channel]) + steps);
  return c;
}

TEST(Float16Bound, RejectsRealBugs) {
  const H100Case c;
  const BlendOutput ref = c.Ref(c.blend);
  // 16 float16 ULPs off (on top of, or instead of, the H100's 3).
  EXPECT_FALSE(CompareBlend(c.format, ref, Moved(c.actual, 0, -16)).ok);
  EXPECT_FALSE(CompareBlend(c.format, ref, Moved(ref.stored, 0, 16)).ok);
  EXPECT_FALSE(CompareBlend(c.format, ref, Moved(ref.stored, 1, 16)).ok);  // G: -337 region, negative: still 16 ULPs
  // 8 ULPs are already out for R: the bound is about 4 there.
  EXPECT_FALSE(CompareBlend(c.format, ref, Moved(ref.stored, 0, 8)).ok);
  // Wrong factor: DestBlend SRC1_COLOR instead of INV_SRC1_COLOR.
  RENDER_TARGET_BLEND_DESC wrongFactor = c.blend;
  wrongFactor.DestBlend = BLEND_SRC1_COLOR;
  EXPECT_FALSE(CompareBlend(c.format, ref, c.Ref(wrongFactor).stored).ok);
  // Source and destination factors swapped.
  RENDER_TARGET_BLEND_DESC swapped = c.blend;
  std::swap(swapped.SrcBlend, swapped.DestBlend);
  EXPECT_FALSE(CompareBlend(c.format, ref, c.Ref(swapped).stored).ok);
  // ADD evaluated as SUBTRACT, and as REV_SUBTRACT.
  RENDER_TARGET_BLEND_DESC sub = c.blend;
  sub.BlendOp = BLEND_OP_SUBTRACT;
  EXPECT_FALSE(CompareBlend(c.format, ref, c.Ref(sub).stored).ok);
  sub.BlendOp = BLEND_OP_REV_SUBTRACT;
  EXPECT_FALSE(CompareBlend(c.format, ref, c.Ref(sub).stored).ok);
  // A wrong alpha factor (SRC_ALPHA for INV_SRC_ALPHA) under MAX changes nothing
  // (MAX ignores the factors), so it is not a detectable bug: same bits.
  RENDER_TARGET_BLEND_DESC alphaFactor = c.blend;
  alphaFactor.SrcBlendAlpha = BLEND_SRC_ALPHA;
  EXPECT_EQ(c.Ref(alphaFactor).stored, ref.stored);
}

TEST(Float16Bound, InverseFactorNearOneAllowsTheRoundingOfX) {
  // INV_SRC_ALPHA with As = 0.9990234 + a bit: x converts toward zero to
  // 0.9990234375 (1 - x' = 2^-10), where the exact 1 - x is ~0.00095; the
  // product with Cs = 8 moves by 8 * conv(x). The bound allows that (the rounding
  // of x is most of the factor: FS 17.5 + FS 3.2.2), in ULPs of the result it is
  // many, and twice the allowance is still out.
  constexpr DXGI_FORMAT kFmt = DXGI_FORMAT_R16_FLOAT;
  const float as = 0.99902344f + 3e-5f;
  const RENDER_TARGET_BLEND_DESC b = Blend(BLEND_INV_SRC_ALPHA, BLEND_ZERO, BLEND_OP_ADD);
  const BlendOutput ref = BlendResult(kFmt, b, kOnes, Float4{8.0f, 0, 0, as}, {}, StoredColor{});
  const double device = 8.0 * (1.0 - static_cast<double>(HalfToFloat(FloatToHalf(as, HalfRounding::TowardZero))));
  const StoredColor h100Like{{FloatToHalf(static_cast<float>(device), HalfRounding::TowardZero), 0, 0, 0}};
  const BlendVerdict v = CompareBlend(kFmt, ref, h100Like);
  EXPECT_TRUE(v.ok);
  EXPECT_GT(v.channels[0].steps, 16u);
  const double twice = ref.decoded[0] + 2.0 * (device - ref.decoded[0]) + 2.0 * v.channels[0].bound;
  EXPECT_FALSE(CompareBlend(kFmt, ref, StoredColor{{FloatToHalf(static_cast<float>(twice), HalfRounding::TowardZero), 0, 0, 0}}).ok);
}

TEST(SrcAlphaSat, OutOfRangeReportsBothReadings) {
  // The recorded H100 case: R16G16B16A16_FLOAT, RGB SRC_ALPHA_SAT/INV_SRC_ALPHA/ADD,
  // alpha DEST_ALPHA/ONE/ADD, As = 0, Ad = 0x3f0d (1.7626953125):
  // f = min(0, 1 - 1.763) = -0.763 (FS 17.1 formula) or 0 (saturated). The H100
  // kept the destination, the saturated reading exactly.
  constexpr DXGI_FORMAT kFmt = DXGI_FORMAT_R16G16B16A16_FLOAT;
  RENDER_TARGET_BLEND_DESC b = Blend(BLEND_SRC_ALPHA_SAT, BLEND_INV_SRC_ALPHA, BLEND_OP_ADD);
  b.SrcBlendAlpha = BLEND_DEST_ALPHA;
  b.DestBlendAlpha = BLEND_ONE;
  const StoredColor dest{{0xbcb7, 0x4193, 0xbd68, 0x3f0d}};
  const BlendOutput ref = BlendResult(kFmt, b, Float4{2.32273436f, -1.64107597f, 0.132224798f, 2.84858418f},
                                      Float4{38.7201614f, 1.30498123f, 2.25068426f, 0.0f}, {}, dest);
  EXPECT_EQ(ref.stored, (StoredColor{{0xcfad, 0x3f2a, 0xc222, 0x3f0d}}));  // the formula, as recorded
  ASSERT_TRUE(ref.hasSaturatedReading);
  EXPECT_EQ(ref.saturated.stored, dest);
  EXPECT_EQ(ref.saturated.terms.srcFactor[0], 0.0f);
  const BlendVerdict h100 = CompareBlend(kFmt, ref, dest);
  EXPECT_TRUE(h100.ok);
  EXPECT_TRUE(h100.usedSaturatedReading);
  const BlendVerdict formula = CompareBlend(kFmt, ref, ref.stored);
  EXPECT_TRUE(formula.ok);
  EXPECT_FALSE(formula.usedSaturatedReading);
  // Neither reading: f = 1 (clamped the wrong way) is rejected.
  RENDER_TARGET_BLEND_DESC one = b;
  one.SrcBlend = BLEND_ONE;
  EXPECT_FALSE(CompareBlend(kFmt, ref, BlendResult(kFmt, one, kOnes, Float4{38.7201614f, 1.30498123f, 2.25068426f, 0.0f},
                                                    {}, dest).stored).ok);
  // A pixel may not mix the readings channel by channel: R from one, G from the other.
  StoredColor mixed = dest;
  mixed.bits[0] = ref.stored.bits[0];
  EXPECT_FALSE(CompareBlend(kFmt, ref, mixed).ok);
}

TEST(SrcAlphaSat, InRangeHasOneReading) {
  // f within [0, 1], and every UNORM case (inputs clamped first, FS 17.5): one reading.
  RENDER_TARGET_BLEND_DESC b = Blend(BLEND_SRC_ALPHA_SAT, BLEND_ONE, BLEND_OP_ADD);
  EXPECT_FALSE(BlendResult(DXGI_FORMAT_R16G16B16A16_FLOAT, b, kOnes, Float4{1, 1, 1, 0.25f}, {},
                           Encode(DXGI_FORMAT_R16G16B16A16_FLOAT, Float4{0, 0, 0, 0.5f}))
                   .hasSaturatedReading);
  EXPECT_FALSE(BlendResult(DXGI_FORMAT_R8G8B8A8_UNORM, b, kOnes, Float4{1, 1, 1, 1.5f}, {},
                           StoredColor{{0, 0, 0, 0}})
                   .hasSaturatedReading);
  // Above 1 on a float target: As = 3, Ad = -1: f = 2 or 1.
  const BlendOutput above = BlendResult(DXGI_FORMAT_R32G32B32A32_FLOAT, b, kOnes, Float4{1, 1, 1, 3}, {},
                                        Encode(DXGI_FORMAT_R32G32B32A32_FLOAT, Float4{0, 0, 0, -1}));
  ASSERT_TRUE(above.hasSaturatedReading);
  EXPECT_EQ(above.decoded[0], 2.0f);
  EXPECT_EQ(above.saturated.decoded[0], 1.0f);
  // SRC_ALPHA_SAT only in the alpha blend (factor 1 there): no second reading.
  RENDER_TARGET_BLEND_DESC alphaOnly = Blend(BLEND_ONE, BLEND_ONE, BLEND_OP_ADD);
  alphaOnly.SrcBlendAlpha = BLEND_SRC_ALPHA_SAT;
  EXPECT_FALSE(BlendResult(DXGI_FORMAT_R32G32B32A32_FLOAT, alphaOnly, kOnes, Float4{1, 1, 1, 3}, {},
                           Encode(DXGI_FORMAT_R32G32B32A32_FLOAT, Float4{0, 0, 0, -1}))
                   .hasSaturatedReading);
}

TEST(TermBound, UintStaysExact) {
  constexpr DXGI_FORMAT kFmt = DXGI_FORMAT_R32_UINT;
  const BlendOutput ref = BlendResult(kFmt, Blend(BLEND_ONE, BLEND_ONE, BLEND_OP_SUBTRACT), kOnes,
                                      UintRegister(42, 0, 0, 0), {}, StoredColor{{40, 0, 0, 0}});
  EXPECT_TRUE(CompareBlend(kFmt, ref, StoredColor{{42, 0, 0, 0}}).ok);
  EXPECT_FALSE(CompareBlend(kFmt, ref, StoredColor{{43, 0, 0, 0}}).ok);
}

}  // namespace
}  // namespace rhi::reference
