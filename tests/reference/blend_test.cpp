// BlendResult on known pixels. Most factor and op tests use R32G32B32A32_FLOAT,
// where every value below is a sum of powers of two and the arithmetic is exact;
// the format-specific tests use the formats they are about.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <stdexcept>

#include "rhi_reference/blend.h"
#include "rhi_reference/float16.h"

namespace rhi::reference {
namespace {

constexpr DXGI_FORMAT kFloat4 = DXGI_FORMAT_R32G32B32A32_FLOAT;
constexpr DXGI_FORMAT kRgba8 = DXGI_FORMAT_R8G8B8A8_UNORM;

// The known pixel.
const Float4 kSrc0{0.5f, 0.25f, 0.75f, 0.625f};
const Float4 kSrc1{0.125f, 0.375f, 0.875f, 0.25f};
const Float4 kDest{0.25f, 0.5f, 1.0f, 0.75f};
const Float4 kBlendFactor{0.5f, 0.75f, 0.25f, 0.125f};
const Float4 kDefaultFactor{1.0f, 1.0f, 1.0f, 1.0f};

RENDER_TARGET_BLEND_DESC Enabled(BLEND src, BLEND dest, BLEND_OP op, BLEND srcAlpha, BLEND destAlpha,
                                 BLEND_OP opAlpha) {
  RENDER_TARGET_BLEND_DESC blend;
  blend.BlendEnable = TRUE;
  blend.SrcBlend = src;
  blend.DestBlend = dest;
  blend.BlendOp = op;
  blend.SrcBlendAlpha = srcAlpha;
  blend.DestBlendAlpha = destAlpha;
  blend.BlendOpAlpha = opAlpha;
  return blend;
}

Float4 BlendFloat4(const RENDER_TARGET_BLEND_DESC& blend) {
  return BlendResult(kFloat4, blend, kBlendFactor, kSrc0, kSrc1, Encode(kFloat4, kDest)).decoded;
}

StoredColor Rgba8(uint32_t r, uint32_t g, uint32_t b, uint32_t a) { return StoredColor{{r, g, b, a}}; }

// Each factor as SrcBlend with DestBlend ZERO: result = src0 * factor.
// src0 = (0.5, 0.25, 0.75, 0.625); the factor values are in the comments.
struct FactorCase {
  BLEND factor;
  Float4 expected;  // alpha only checked when the factor is valid for alpha (FS 17.2)
  bool validForAlpha;
};

const FactorCase kFactorCases[] = {
    {BLEND_ZERO, {0, 0, 0, 0}, true},
    {BLEND_ONE, {0.5f, 0.25f, 0.75f, 0.625f}, true},
    // SRC_COLOR (0.5, 0.25, 0.75): 0.25, 0.0625, 0.5625
    {BLEND_SRC_COLOR, {0.25f, 0.0625f, 0.5625f, 0}, false},
    // INV_SRC_COLOR (0.5, 0.75, 0.25): 0.25, 0.1875, 0.1875
    {BLEND_INV_SRC_COLOR, {0.25f, 0.1875f, 0.1875f, 0}, false},
    // SRC_ALPHA 0.625: 0.3125, 0.15625, 0.46875, a 0.390625
    {BLEND_SRC_ALPHA, {0.3125f, 0.15625f, 0.46875f, 0.390625f}, true},
    // INV_SRC_ALPHA 0.375: 0.1875, 0.09375, 0.28125, a 0.234375
    {BLEND_INV_SRC_ALPHA, {0.1875f, 0.09375f, 0.28125f, 0.234375f}, true},
    // DEST_ALPHA 0.75: 0.375, 0.1875, 0.5625, a 0.46875
    {BLEND_DEST_ALPHA, {0.375f, 0.1875f, 0.5625f, 0.46875f}, true},
    // INV_DEST_ALPHA 0.25: 0.125, 0.0625, 0.1875, a 0.15625
    {BLEND_INV_DEST_ALPHA, {0.125f, 0.0625f, 0.1875f, 0.15625f}, true},
    // DEST_COLOR (0.25, 0.5, 1): 0.125, 0.125, 0.75
    {BLEND_DEST_COLOR, {0.125f, 0.125f, 0.75f, 0}, false},
    // INV_DEST_COLOR (0.75, 0.5, 0): 0.375, 0.125, 0
    {BLEND_INV_DEST_COLOR, {0.375f, 0.125f, 0.0f, 0}, false},
    // SRC_ALPHA_SAT f = min(0.625, 1 - 0.75) = 0.25; alpha factor 1:
    // 0.125, 0.0625, 0.1875, a 0.625
    {BLEND_SRC_ALPHA_SAT, {0.125f, 0.0625f, 0.1875f, 0.625f}, true},
    // BLEND_FACTOR (0.5, 0.75, 0.25, 0.125): 0.25, 0.1875, 0.1875, a 0.078125
    {BLEND_BLEND_FACTOR, {0.25f, 0.1875f, 0.1875f, 0.078125f}, true},
    // INV_BLEND_FACTOR (0.5, 0.25, 0.75, 0.875): 0.25, 0.0625, 0.5625, a 0.546875
    {BLEND_INV_BLEND_FACTOR, {0.25f, 0.0625f, 0.5625f, 0.546875f}, true},
    // SRC1_COLOR (0.125, 0.375, 0.875): 0.0625, 0.09375, 0.65625
    {BLEND_SRC1_COLOR, {0.0625f, 0.09375f, 0.65625f, 0}, false},
    // INV_SRC1_COLOR (0.875, 0.625, 0.125): 0.4375, 0.15625, 0.09375
    {BLEND_INV_SRC1_COLOR, {0.4375f, 0.15625f, 0.09375f, 0}, false},
    // SRC1_ALPHA 0.25: 0.125, 0.0625, 0.1875, a 0.15625
    {BLEND_SRC1_ALPHA, {0.125f, 0.0625f, 0.1875f, 0.15625f}, true},
    // INV_SRC1_ALPHA 0.75: 0.375, 0.1875, 0.5625, a 0.46875
    {BLEND_INV_SRC1_ALPHA, {0.375f, 0.1875f, 0.5625f, 0.46875f}, true},
};

TEST(Blend, EachFactorAsSourceFactor) {
  for (const FactorCase& c : kFactorCases) {
    const BLEND alphaFactor = c.validForAlpha ? c.factor : BLEND_ONE;
    const Float4 out = BlendFloat4(Enabled(c.factor, BLEND_ZERO, BLEND_OP_ADD, alphaFactor, BLEND_ZERO, BLEND_OP_ADD));
    SCOPED_TRACE(testing::Message() << "factor " << c.factor);
    EXPECT_EQ(out[0], c.expected[0]);
    EXPECT_EQ(out[1], c.expected[1]);
    EXPECT_EQ(out[2], c.expected[2]);
    EXPECT_EQ(out[3], c.validForAlpha ? c.expected[3] : 0.625f);
  }
}

TEST(Blend, FactorsAsDestinationFactor) {
  // dest = (0.25, 0.5, 1, 0.75). DestBlend SRC_COLOR: (0.125, 0.125, 0.75);
  // DestBlendAlpha INV_SRC_ALPHA: 0.75 * 0.375 = 0.28125.
  EXPECT_EQ(BlendFloat4(Enabled(BLEND_ZERO, BLEND_SRC_COLOR, BLEND_OP_ADD, BLEND_ZERO, BLEND_INV_SRC_ALPHA,
                                BLEND_OP_ADD)),
            (Float4{0.125f, 0.125f, 0.75f, 0.28125f}));
  // DestBlend DEST_COLOR squares the destination: (0.0625, 0.25, 1); alpha DEST_ALPHA 0.5625.
  EXPECT_EQ(BlendFloat4(Enabled(BLEND_ZERO, BLEND_DEST_COLOR, BLEND_OP_ADD, BLEND_ZERO, BLEND_DEST_ALPHA,
                                BLEND_OP_ADD)),
            (Float4{0.0625f, 0.25f, 1.0f, 0.5625f}));
}

TEST(Blend, SrcAlphaSatTakesTheSmallerOfSourceAlphaAndInverseDestAlpha) {
  // src alpha 0.125 < 1 - 0.75: f = 0.125, so rgb = (0.5, 0.25, 0.75) * 0.125
  // = (0.0625, 0.03125, 0.09375); the alpha factor is 1: alpha 0.125.
  const Float4 src{0.5f, 0.25f, 0.75f, 0.125f};
  const auto blend = Enabled(BLEND_SRC_ALPHA_SAT, BLEND_ZERO, BLEND_OP_ADD, BLEND_SRC_ALPHA_SAT, BLEND_ZERO,
                             BLEND_OP_ADD);
  EXPECT_EQ(BlendResult(kFloat4, blend, kDefaultFactor, src, src, Encode(kFloat4, kDest)).decoded,
            (Float4{0.0625f, 0.03125f, 0.09375f, 0.125f}));
}

TEST(Blend, EachOp) {
  // ONE/ONE, src (0.5, 0.25, 0.75, 0.625), dest (0.25, 0.5, 1, 0.75).
  const auto op = [](BLEND_OP o) { return BlendFloat4(Enabled(BLEND_ONE, BLEND_ONE, o, BLEND_ONE, BLEND_ONE, o)); };
  EXPECT_EQ(op(BLEND_OP_ADD), (Float4{0.75f, 0.75f, 1.75f, 1.375f}));
  EXPECT_EQ(op(BLEND_OP_SUBTRACT), (Float4{0.25f, -0.25f, -0.25f, -0.125f}));     // src - dest
  EXPECT_EQ(op(BLEND_OP_REV_SUBTRACT), (Float4{-0.25f, 0.25f, 0.25f, 0.125f}));   // dest - src
  EXPECT_EQ(op(BLEND_OP_MIN), (Float4{0.25f, 0.25f, 0.75f, 0.625f}));
  EXPECT_EQ(op(BLEND_OP_MAX), (Float4{0.5f, 0.5f, 1.0f, 0.75f}));
}

TEST(Blend, MinAndMaxIgnoreTheFactors) {
  // With ZERO/ZERO factors an ADD would give 0; MIN and MAX still see the raw
  // colours (FS 17.1): the same results as in EachOp.
  const auto op = [](BLEND_OP o) {
    return BlendFloat4(Enabled(BLEND_ZERO, BLEND_ZERO, o, BLEND_ZERO, BLEND_ZERO, o));
  };
  EXPECT_EQ(op(BLEND_OP_MIN), (Float4{0.25f, 0.25f, 0.75f, 0.625f}));
  EXPECT_EQ(op(BLEND_OP_MAX), (Float4{0.5f, 0.5f, 1.0f, 0.75f}));
  // Same with INV_SRC_ALPHA / SRC_COLOR factors that would scale the terms.
  EXPECT_EQ(BlendFloat4(Enabled(BLEND_INV_SRC_ALPHA, BLEND_SRC_COLOR, BLEND_OP_MAX, BLEND_SRC_ALPHA,
                                BLEND_ZERO, BLEND_OP_MIN)),
            (Float4{0.5f, 0.5f, 1.0f, 0.625f}));
}

TEST(Blend, SeparateRgbAndAlpha) {
  // RGB: SRC_ALPHA / INV_SRC_ALPHA ADD = src*0.625 + dest*0.375
  //   r 0.3125 + 0.09375 = 0.40625, g 0.15625 + 0.1875 = 0.34375, b 0.46875 + 0.375 = 0.84375.
  // Alpha: ONE / ONE REV_SUBTRACT = 0.75 - 0.625 = 0.125.
  EXPECT_EQ(BlendFloat4(Enabled(BLEND_SRC_ALPHA, BLEND_INV_SRC_ALPHA, BLEND_OP_ADD, BLEND_ONE, BLEND_ONE,
                                BLEND_OP_REV_SUBTRACT)),
            (Float4{0.40625f, 0.34375f, 0.84375f, 0.125f}));
}

TEST(Blend, DualSource) {
  // FS 17.6 example: SrcBlend ONE, DestBlend SRC1_COLOR: src0 + dest * src1
  //   = (0.5 + 0.25*0.125, 0.25 + 0.5*0.375, 0.75 + 1*0.875) = (0.53125, 0.4375, 1.625).
  // Alpha: ONE / SRC1_ALPHA: 0.625 + 0.75*0.25 = 0.8125.
  EXPECT_EQ(BlendFloat4(Enabled(BLEND_ONE, BLEND_SRC1_COLOR, BLEND_OP_ADD, BLEND_ONE, BLEND_SRC1_ALPHA,
                                BLEND_OP_ADD)),
            (Float4{0.53125f, 0.4375f, 1.625f, 0.8125f}));
  // o1 as the per-channel weight: SRC1_COLOR / INV_SRC1_COLOR
  //   r 0.5*0.125 + 0.25*0.875 = 0.28125, g 0.25*0.375 + 0.5*0.625 = 0.40625,
  //   b 0.75*0.875 + 1*0.125 = 0.78125; alpha SRC1_ALPHA/INV_SRC1_ALPHA
  //   0.625*0.25 + 0.75*0.75 = 0.71875.
  EXPECT_EQ(BlendFloat4(Enabled(BLEND_SRC1_COLOR, BLEND_INV_SRC1_COLOR, BLEND_OP_ADD, BLEND_SRC1_ALPHA,
                                BLEND_INV_SRC1_ALPHA, BLEND_OP_ADD)),
            (Float4{0.28125f, 0.40625f, 0.78125f, 0.71875f}));
}

TEST(Blend, BlendFactorIsClampedOnUnormButNotOnFloat) {
  // Factor (2, -1, 0.5, 0.5), SrcBlend BLEND_FACTOR, src (0.4, 0.4, 0.4, 1).
  // UNORM clamps the factor to (1, 0, 0.5, 0.5): 0.4 -> 0.4*255+0.5 = 102.5 -> 102,
  // 0 -> 0, 0.2 -> 51.5 -> 51, alpha 0.5 -> 128.
  const Float4 factor{2.0f, -1.0f, 0.5f, 0.5f};
  const Float4 src{0.4f, 0.4f, 0.4f, 1.0f};
  const auto blend = Enabled(BLEND_BLEND_FACTOR, BLEND_ZERO, BLEND_OP_ADD, BLEND_BLEND_FACTOR, BLEND_ZERO,
                             BLEND_OP_ADD);
  EXPECT_EQ(BlendResult(kRgba8, blend, factor, src, src, Rgba8(0, 0, 0, 0)).stored, Rgba8(102, 0, 51, 128));
  // float32: no clamp: (0.8, -0.4, 0.2, 0.5).
  const Float4 out = BlendResult(kFloat4, blend, factor, src, src, Encode(kFloat4, {})).decoded;
  EXPECT_FLOAT_EQ(out[0], 0.8f);
  EXPECT_FLOAT_EQ(out[1], -0.4f);
  EXPECT_FLOAT_EQ(out[2], 0.2f);
  EXPECT_FLOAT_EQ(out[3], 0.5f);
}

TEST(Blend, WriteMaskKeepsMaskedChannels) {
  // Blend off, src all 1, dest codes (10, 20, 30, 40), mask R|A -> (255, 20, 30, 255).
  RENDER_TARGET_BLEND_DESC blend;
  blend.RenderTargetWriteMask = COLOR_WRITE_ENABLE_RED | COLOR_WRITE_ENABLE_ALPHA;
  EXPECT_EQ(BlendResult(kRgba8, blend, kDefaultFactor, {1, 1, 1, 1}, {}, Rgba8(10, 20, 30, 40)).stored,
            Rgba8(255, 20, 30, 255));
  // Mask 0: nothing changes, even with blending on.
  auto add = Enabled(BLEND_ONE, BLEND_ONE, BLEND_OP_ADD, BLEND_ONE, BLEND_ONE, BLEND_OP_ADD);
  add.RenderTargetWriteMask = 0;
  EXPECT_EQ(BlendResult(kRgba8, add, kDefaultFactor, {1, 1, 1, 1}, {}, Rgba8(10, 20, 30, 40)).stored,
            Rgba8(10, 20, 30, 40));
}

TEST(Blend, IndependentBlendEnableFalseUsesTarget0ForEveryTarget) {
  // RT[0]: ONE/ONE ADD, write mask R|G|B. RT[1]: blending off, all channels.
  // Target 1, src (0.25, 0.25, 0.25, 0.25), dest codes (64, 64, 64, 64):
  //   with RT[0]'s settings: 0.25 + 64/255 = 0.50098 -> 128.25 -> 128, alpha kept 64;
  //   with its own settings: 0.25 -> 64.25 -> 64 everywhere.
  BLEND_DESC desc;
  desc.RenderTarget[0] = Enabled(BLEND_ONE, BLEND_ONE, BLEND_OP_ADD, BLEND_ONE, BLEND_ONE, BLEND_OP_ADD);
  desc.RenderTarget[0].RenderTargetWriteMask =
      COLOR_WRITE_ENABLE_RED | COLOR_WRITE_ENABLE_GREEN | COLOR_WRITE_ENABLE_BLUE;
  const Float4 src{0.25f, 0.25f, 0.25f, 0.25f};
  desc.IndependentBlendEnable = FALSE;
  EXPECT_EQ(&TargetBlendDesc(desc, 1), &desc.RenderTarget[0]);
  EXPECT_EQ(BlendResult(kRgba8, desc, 1, kDefaultFactor, src, src, Rgba8(64, 64, 64, 64)).stored,
            Rgba8(128, 128, 128, 64));
  desc.IndependentBlendEnable = TRUE;
  EXPECT_EQ(BlendResult(kRgba8, desc, 1, kDefaultFactor, src, src, Rgba8(64, 64, 64, 64)).stored,
            Rgba8(64, 64, 64, 64));
  EXPECT_THROW(TargetBlendDesc(desc, 8), std::out_of_range);  // only 8 targets
}

TEST(Blend, UnormClampsTheSourceBeforeBlending) {
  // Blend off: (1.5, -0.5, 0.5, 2) -> (255, 0, 128, 255).
  RENDER_TARGET_BLEND_DESC off;
  EXPECT_EQ(BlendResult(kRgba8, off, kDefaultFactor, {1.5f, -0.5f, 0.5f, 2.0f}, {}, Rgba8(0, 0, 0, 0)).stored,
            Rgba8(255, 0, 128, 255));
  // SUBTRACT src - dest, src r 1.5 clamped to 1 first, dest 153 (0.6):
  //   1 - 0.6 = 0.4 -> 102 (unclamped would be 0.9 -> 230).
  // REV_SUBTRACT dest - src on alpha, src -0.5 clamped to 0: 0.6 -> 153
  //   (unclamped 1.1 -> 255).
  const auto blend = Enabled(BLEND_ONE, BLEND_ONE, BLEND_OP_SUBTRACT, BLEND_ONE, BLEND_ONE, BLEND_OP_REV_SUBTRACT);
  EXPECT_EQ(BlendResult(kRgba8, blend, kDefaultFactor, {1.5f, 1.5f, 1.5f, -0.5f}, {}, Rgba8(153, 153, 153, 153))
                .stored,
            Rgba8(102, 102, 102, 153));
}

TEST(Blend, UnormClampsTheResult) {
  // ONE/ONE ADD 0.75 + 0.75 = 1.5 -> 255; SUBTRACT 0.25 - 0.75 = -0.5 -> 0.
  // src 0.75 and dest 191 (0.74902): 1.49902 -> 255 and 0.25 - 0.74902 -> 0.
  const auto add = Enabled(BLEND_ONE, BLEND_ONE, BLEND_OP_ADD, BLEND_ONE, BLEND_ONE, BLEND_OP_SUBTRACT);
  EXPECT_EQ(BlendResult(kRgba8, add, kDefaultFactor, {0.75f, 0.75f, 0.75f, 0.25f}, {}, Rgba8(191, 191, 191, 191))
                .stored,
            Rgba8(255, 255, 255, 0));
}

TEST(Blend, ClassicOverOnUnorm) {
  // SRC_ALPHA / INV_SRC_ALPHA, src (1, 0, 0, 0.5) over dest (0, 0, 255, 255):
  //   r 0.5 -> 128, g 0, b 0.5 -> 128; alpha ONE/INV_SRC_ALPHA 0.5 + 1*0.5 = 1 -> 255.
  const auto over = Enabled(BLEND_SRC_ALPHA, BLEND_INV_SRC_ALPHA, BLEND_OP_ADD, BLEND_ONE, BLEND_INV_SRC_ALPHA,
                            BLEND_OP_ADD);
  EXPECT_EQ(BlendResult(kRgba8, over, kDefaultFactor, {1, 0, 0, 0.5f}, {}, Rgba8(0, 0, 255, 255)).stored,
            Rgba8(128, 0, 128, 255));
}

TEST(Blend, FloatTargetsDoNotClamp) {
  // Blend off: 2.5 stays 2.5 in float32 and in float16 (0x4100).
  RENDER_TARGET_BLEND_DESC off;
  const Float4 src{2.5f, -3.0f, 100.0f, 2.5f};
  EXPECT_EQ(BlendResult(kFloat4, off, kDefaultFactor, src, {}, Encode(kFloat4, {})).decoded, src);
  EXPECT_EQ(BlendResult(DXGI_FORMAT_R16G16B16A16_FLOAT, off, kDefaultFactor, src, {}, StoredColor{}).stored,
            (StoredColor{{0x4100, 0xC200, 0x5640, 0x4100}}));  // -3 = 0xC200, 100 = 2^6*1.5625 = 0x5640
  // ONE/ONE: 2.5 + 0.25 = 2.75, not clamped to 1.
  const auto add = Enabled(BLEND_ONE, BLEND_ONE, BLEND_OP_ADD, BLEND_ONE, BLEND_ONE, BLEND_OP_ADD);
  EXPECT_EQ(BlendResult(kFloat4, add, kDefaultFactor, src, {}, Encode(kFloat4, {0.25f, 0.25f, 0.25f, 0.25f}))
                .decoded,
            (Float4{2.75f, -2.75f, 100.25f, 2.75f}));
}

TEST(Blend, Float16TargetStoresRoundedTowardZero) {
  constexpr DXGI_FORMAT kR16 = DXGI_FORMAT_R16_FLOAT;
  RENDER_TARGET_BLEND_DESC off;
  const auto write = [&](float value) {
    return BlendResult(kR16, off, kDefaultFactor, {value, 0, 0, 0}, {}, StoredColor{}).stored.bits[0];
  };
  EXPECT_EQ(write(1.0f / 3.0f), 0x3555u);  // 0.333251953125
  // 65520: D3D11 stores the largest finite value, not INF (FS 3.2.2).
  EXPECT_EQ(write(65520.0f), 0x7BFFu);
  EXPECT_EQ(write(INFINITY), 0x7C00u);
  // 1.5 * 2^-24 -> one denorm unit (toward zero).
  EXPECT_EQ(write(std::ldexp(1.5f, -24)), 0x0001u);
  // Blended: dest 1.0 (0x3C00) + src 3 * 2^-12 = 1.000732421875, 0.75 ULP above 1:
  // toward zero 0x3C00 (nearest-even would give 0x3C01).
  const auto add = Enabled(BLEND_ONE, BLEND_ONE, BLEND_OP_ADD, BLEND_ONE, BLEND_ONE, BLEND_OP_ADD);
  EXPECT_EQ(BlendResult(kR16, add, kDefaultFactor, {std::ldexp(3.0f, -12), 0, 0, 0}, {},
                        StoredColor{{0x3C00, 0, 0, 0}})
                .stored.bits[0],
            0x3C00u);
  // Missing alpha reads 1: DEST_ALPHA on R16_FLOAT multiplies by 1: 0.5 -> 0x3800.
  const auto destAlpha = Enabled(BLEND_DEST_ALPHA, BLEND_ZERO, BLEND_OP_ADD, BLEND_ONE, BLEND_ZERO, BLEND_OP_ADD);
  EXPECT_EQ(BlendResult(kR16, destAlpha, kDefaultFactor, {0.5f, 0, 0, 0}, {}, StoredColor{}).stored.bits[0],
            0x3800u);
}

TEST(Blend, SrgbBlendsInLinearSpace) {
  // dest code 128 -> linear 0.2158605; src linear 0.5 with alpha 0.25,
  // SRC_ALPHA / INV_SRC_ALPHA: 0.5*0.25 + 0.2158605*0.75 = 0.2868954 linear
  //   -> sRGB 1.055*0.2868954^(1/2.4) - 0.055 = 0.5720526 -> *255 + 0.5 = 146.37 -> 146.
  // Blending the encoded values instead would give 0.125 + 0.75*0.50196 -> 128.
  // Alpha is stored linear: ONE / INV_SRC_ALPHA 0.25 + 0.75*0.50196 = 0.6264706
  //   -> 159.75 + 0.5 -> 160.
  const auto over = Enabled(BLEND_SRC_ALPHA, BLEND_INV_SRC_ALPHA, BLEND_OP_ADD, BLEND_ONE, BLEND_INV_SRC_ALPHA,
                            BLEND_OP_ADD);
  const BlendOutput out = BlendResult(DXGI_FORMAT_R8G8B8A8_UNORM_SRGB, over, kDefaultFactor,
                                      {0.5f, 0.5f, 0.5f, 0.25f}, {}, Rgba8(128, 128, 128, 128));
  EXPECT_EQ(out.stored, Rgba8(146, 146, 146, 160));
  // Decoded is linear: code 146 -> ((146/255 + 0.055)/1.055)^2.4 = 0.2874409.
  EXPECT_NEAR(out.decoded[0], 0.2874409f, 1e-6f);
}

TEST(Blend, B8G8R8X8DestinationAlphaIsOne) {
  // The X byte holds 0, yet DEST_ALPHA reads 1 and INV_DEST_ALPHA 0: the result is
  // the source, (0.4, 0.6, 0.8) -> (102, 153, 204).
  const auto blend = Enabled(BLEND_DEST_ALPHA, BLEND_INV_DEST_ALPHA, BLEND_OP_ADD, BLEND_ONE, BLEND_ZERO,
                             BLEND_OP_ADD);
  const BlendOutput out = BlendResult(DXGI_FORMAT_B8G8R8X8_UNORM, blend, kDefaultFactor, {0.4f, 0.6f, 0.8f, 0.3f},
                                      {}, Rgba8(10, 20, 30, 0));
  EXPECT_EQ(out.stored, Rgba8(102, 153, 204, 0));
  EXPECT_EQ(out.decoded[3], 1.0f);
}

TEST(Blend, R10G10B10A2AlphaIsQuantisedToTwoBits) {
  // Dest alpha code 1 = 1/3. DEST_ALPHA / ZERO on RGB: src 0.9 * 1/3 = 0.3 ->
  //   0.3*1023 + 0.5 = 307.4 -> 307. Alpha ONE/ZERO: src 0.5 -> 2.
  const auto blend = Enabled(BLEND_DEST_ALPHA, BLEND_ZERO, BLEND_OP_ADD, BLEND_ONE, BLEND_ZERO, BLEND_OP_ADD);
  EXPECT_EQ(BlendResult(DXGI_FORMAT_R10G10B10A2_UNORM, blend, kDefaultFactor, {0.9f, 0.9f, 0.9f, 0.5f}, {},
                        StoredColor{{0, 0, 0, 1}})
                .stored,
            (StoredColor{{307, 307, 307, 2}}));
  // Alpha ADD ONE/ONE: 1/3 + 0.2 = 0.5333 -> 0.5333*3 + 0.5 = 2.1 -> 2.
  const auto add = Enabled(BLEND_ZERO, BLEND_ONE, BLEND_OP_ADD, BLEND_ONE, BLEND_ONE, BLEND_OP_ADD);
  EXPECT_EQ(BlendResult(DXGI_FORMAT_R10G10B10A2_UNORM, add, kDefaultFactor, {0, 0, 0, 0.2f}, {},
                        StoredColor{{0, 0, 0, 1}})
                .stored.bits[3],
            2u);
}

TEST(Blend, IntegerTargetsAreNeverBlended) {
  // R32_UINT, ONE/ONE ADD enabled: dest 5, shader writes 7 -> 7, not 12.
  const auto add = Enabled(BLEND_ONE, BLEND_ONE, BLEND_OP_ADD, BLEND_ONE, BLEND_ONE, BLEND_OP_ADD);
  EXPECT_EQ(BlendResult(DXGI_FORMAT_R32_UINT, add, kDefaultFactor, UintRegister(7, 0, 0, 0), {},
                        StoredColor{{5, 0, 0, 0}})
                .stored.bits[0],
            7u);
  // R32G32B32A32_UINT with write mask G: dest (1, 2, 3, 4), src (10, 20, 30, 40) -> (1, 20, 3, 4).
  auto masked = add;
  masked.RenderTargetWriteMask = COLOR_WRITE_ENABLE_GREEN;
  EXPECT_EQ(BlendResult(DXGI_FORMAT_R32G32B32A32_UINT, masked, kDefaultFactor, UintRegister(10, 20, 30, 40), {},
                        StoredColor{{1, 2, 3, 4}})
                .stored,
            (StoredColor{{1, 20, 3, 4}}));
  // Values a float conversion would mangle go through bit for bit: 0xFFFFFFFF.
  EXPECT_EQ(BlendResult(DXGI_FORMAT_R32_UINT, add, kDefaultFactor, UintRegister(0xFFFFFFFFu, 0, 0, 0), {},
                        StoredColor{})
                .stored.bits[0],
            0xFFFFFFFFu);
}

TEST(Blend, NanPropagatesOnFloatAndBecomesZeroOnUnorm) {
  // FS 17.5: NaN propagates through blending, even times a zero weight.
  const auto add = Enabled(BLEND_ONE, BLEND_ZERO, BLEND_OP_ADD, BLEND_ONE, BLEND_ZERO, BLEND_OP_ADD);
  const Float4 out =
      BlendResult(kFloat4, add, kDefaultFactor, {NAN, 0.5f, 0.5f, 0.5f}, {}, Encode(kFloat4, {})).decoded;
  EXPECT_TRUE(std::isnan(out[0]));
  // UNORM: NaN -> 0 (FS 3.2.3.6).
  EXPECT_EQ(BlendResult(kRgba8, add, kDefaultFactor, {NAN, 0.5f, 0.5f, 0.5f}, {}, Rgba8(9, 9, 9, 9)).stored,
            Rgba8(0, 128, 128, 128));
}

}  // namespace
}  // namespace rhi::reference
