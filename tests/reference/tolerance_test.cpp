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
  EXPECT_EQ(BlendTermK(DXGI_FORMAT_R16_FLOAT, 0).k, 2.25);
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

TEST(TermBound, Float16Cancellation) {
  // ONE/ONE/SUBTRACT of (1 + 2^-10) and 1 in float16: result 2^-10. The
  // operands' magnitude m = |Cs| + |Cd| + |Cd| ~ 3, ULP16(m) = 2^-9, bound
  // 2.25 * 2^-9: 4 * 2^-10 (3 ULP16 of the result away) inside, 6 * 2^-10 outside.
  constexpr DXGI_FORMAT kFmt = DXGI_FORMAT_R16_FLOAT;
  const float ulp = std::ldexp(1.0f, -10);
  const BlendOutput ref = BlendResult(kFmt, Blend(BLEND_ONE, BLEND_ONE, BLEND_OP_SUBTRACT), kOnes,
                                      Float4{1.0f + ulp, 0, 0, 0}, {}, Encode(kFmt, Float4{1.0f, 0, 0, 0}));
  ASSERT_EQ(ref.decoded[0], ulp);
  const BlendVerdict in = CompareBlend(kFmt, ref, Encode(kFmt, Float4{4 * ulp, 0, 0, 0}));
  EXPECT_TRUE(in.ok);
  EXPECT_TRUE(in.usedTermBound);
  EXPECT_FALSE(CompareBlend(kFmt, ref, Encode(kFmt, Float4{6 * ulp, 0, 0, 0})).ok);
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
