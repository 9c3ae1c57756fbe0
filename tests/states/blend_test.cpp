#include "states/blend.h"

#include <gtest/gtest.h>

#include <cstring>
#include <new>
#include <ostream>
#include <string>

namespace rhi::states {
namespace {

BLEND_DESC Independent() {
  BLEND_DESC d;
  d.IndependentBlendEnable = TRUE;
  return d;
}

RENDER_TARGET_BLEND_DESC AlphaBlend() {
  RENDER_TARGET_BLEND_DESC rt;
  rt.BlendEnable = TRUE;
  rt.SrcBlend = BLEND_SRC_ALPHA;
  rt.DestBlend = BLEND_INV_SRC_ALPHA;
  rt.BlendOp = BLEND_OP_ADD;
  rt.SrcBlendAlpha = BLEND_ONE;
  rt.DestBlendAlpha = BLEND_INV_SRC_ALPHA;
  rt.BlendOpAlpha = BLEND_OP_ADD;
  return rt;
}

TEST(BlendValidate, DefaultDescIsValid) { EXPECT_EQ(Validate(BLEND_DESC{}), ""); }

// A device without blending for a format (Vulkan's optional float32 blending)
// refuses draws that blend it, and only those.
TEST(BlendCapability, BlendingAFormatTheDeviceCannotBlendIsRefusedWithTheReason) {
  RENDER_TARGET_BLEND_DESC rt;
  rt.BlendEnable = TRUE;
  rt.BlendOp = BLEND_OP_MAX;
  BLEND_DESC desc;
  desc.RenderTarget[0] = rt;
  const VkPipelineColorBlendAttachmentState blending = ToVulkan(desc).attachments[0];
  EXPECT_EQ(CheckBlendable(2, "DXGI_FORMAT_R32_FLOAT", blending, false, "GPU X"),
            "render target 2 (DXGI_FORMAT_R32_FLOAT) has blending enabled, but GPU X cannot blend that format (no "
            "VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT)");
  EXPECT_EQ(CheckBlendable(2, "DXGI_FORMAT_R32_FLOAT", blending, true, "GPU X"), "");
  const VkPipelineColorBlendAttachmentState opaque = ToVulkan(BLEND_DESC{}).attachments[0];
  EXPECT_EQ(CheckBlendable(0, "DXGI_FORMAT_R32_FLOAT", opaque, false, "GPU X"), "") << "no blending, nothing to refuse";
}

TEST(BlendValidate, InvalidSrcBlendNamesTargetFieldAndValue) {
  BLEND_DESC d = Independent();
  d.RenderTarget[2] = AlphaBlend();
  d.RenderTarget[2].SrcBlend = static_cast<BLEND>(0);
  EXPECT_EQ(Validate(d), "BLEND_DESC.RenderTarget[2].SrcBlend: 0 is not a valid D3D11_BLEND");
}

TEST(BlendValidate, HolesInTheBlendEnumAreInvalid) {
  BLEND_DESC d;
  d.RenderTarget[0] = AlphaBlend();
  d.RenderTarget[0].DestBlend = static_cast<BLEND>(12);
  EXPECT_EQ(Validate(d), "BLEND_DESC.RenderTarget[0].DestBlend: 12 is not a valid D3D11_BLEND");
  d.RenderTarget[0].DestBlend = static_cast<BLEND>(13);
  EXPECT_EQ(Validate(d), "BLEND_DESC.RenderTarget[0].DestBlend: 13 is not a valid D3D11_BLEND");
  d.RenderTarget[0].DestBlend = static_cast<BLEND>(20);
  EXPECT_EQ(Validate(d), "BLEND_DESC.RenderTarget[0].DestBlend: 20 is not a valid D3D11_BLEND");
}

TEST(BlendValidate, InvalidOps) {
  BLEND_DESC d;
  d.RenderTarget[0] = AlphaBlend();
  d.RenderTarget[0].BlendOp = static_cast<BLEND_OP>(6);
  EXPECT_EQ(Validate(d), "BLEND_DESC.RenderTarget[0].BlendOp: 6 is not a valid D3D11_BLEND_OP");
  d.RenderTarget[0].BlendOp = BLEND_OP_MAX;
  d.RenderTarget[0].BlendOpAlpha = static_cast<BLEND_OP>(0);
  EXPECT_EQ(Validate(d), "BLEND_DESC.RenderTarget[0].BlendOpAlpha: 0 is not a valid D3D11_BLEND_OP");
}

TEST(BlendValidate, InvalidAlphaFactorValue) {
  BLEND_DESC d;
  d.RenderTarget[0] = AlphaBlend();
  d.RenderTarget[0].SrcBlendAlpha = static_cast<BLEND>(99);
  EXPECT_EQ(Validate(d), "BLEND_DESC.RenderTarget[0].SrcBlendAlpha: 99 is not a valid D3D11_BLEND");
}

struct ColorFactorCase {
  BLEND factor;
  const char* name;
};

// Readable test names: the parameter prints as its D3D11 name.
void PrintTo(const ColorFactorCase& c, std::ostream* os) { *os << c.name; }

class AlphaColorFactor : public testing::TestWithParam<ColorFactorCase> {};

TEST_P(AlphaColorFactor, RefusedInSrcAndDestAlpha) {
  BLEND_DESC d;
  d.RenderTarget[0] = AlphaBlend();
  d.RenderTarget[0].DestBlendAlpha = GetParam().factor;
  EXPECT_EQ(Validate(d), std::string("BLEND_DESC.RenderTarget[0].DestBlendAlpha: ") + GetParam().name +
                             " is not allowed for alpha (colour factors are invalid in alpha blend)");
  d.RenderTarget[0].DestBlendAlpha = BLEND_ZERO;
  d.RenderTarget[0].SrcBlendAlpha = GetParam().factor;
  EXPECT_EQ(Validate(d), std::string("BLEND_DESC.RenderTarget[0].SrcBlendAlpha: ") + GetParam().name +
                             " is not allowed for alpha (colour factors are invalid in alpha blend)");
  // The same factor is fine in the colour equation.
  d.RenderTarget[0].SrcBlendAlpha = BLEND_ONE;
  d.RenderTarget[0].SrcBlend = GetParam().factor;
  EXPECT_EQ(Validate(d), "");
}

INSTANTIATE_TEST_SUITE_P(All, AlphaColorFactor,
                         testing::Values(ColorFactorCase{BLEND_SRC_COLOR, "D3D11_BLEND_SRC_COLOR"},
                                         ColorFactorCase{BLEND_INV_SRC_COLOR, "D3D11_BLEND_INV_SRC_COLOR"},
                                         ColorFactorCase{BLEND_DEST_COLOR, "D3D11_BLEND_DEST_COLOR"},
                                         ColorFactorCase{BLEND_INV_DEST_COLOR, "D3D11_BLEND_INV_DEST_COLOR"},
                                         ColorFactorCase{BLEND_SRC1_COLOR, "D3D11_BLEND_SRC1_COLOR"},
                                         ColorFactorCase{BLEND_INV_SRC1_COLOR, "D3D11_BLEND_INV_SRC1_COLOR"}),
                         [](const testing::TestParamInfo<ColorFactorCase>& info) {
                           return std::string(info.param.name + sizeof("D3D11_BLEND_") - 1);
                         });

TEST(BlendValidate, AlphaFactorsThatAreNotColourFactorsAreAccepted) {
  BLEND_DESC d;
  d.RenderTarget[0] = AlphaBlend();
  for (BLEND f : {BLEND_ZERO, BLEND_ONE, BLEND_SRC_ALPHA, BLEND_INV_SRC_ALPHA, BLEND_DEST_ALPHA, BLEND_INV_DEST_ALPHA,
                  BLEND_SRC_ALPHA_SAT, BLEND_BLEND_FACTOR, BLEND_INV_BLEND_FACTOR, BLEND_SRC1_ALPHA,
                  BLEND_INV_SRC1_ALPHA}) {
    d.RenderTarget[0].SrcBlendAlpha = f;
    d.RenderTarget[0].DestBlendAlpha = f;
    EXPECT_EQ(Validate(d), "") << BlendName(f);
  }
}

TEST(BlendValidate, DualSourceFactorsAreLegal) {
  BLEND_DESC d;
  d.RenderTarget[0] = AlphaBlend();
  d.RenderTarget[0].SrcBlend = BLEND_SRC1_COLOR;
  d.RenderTarget[0].DestBlend = BLEND_INV_SRC1_COLOR;
  d.RenderTarget[0].SrcBlendAlpha = BLEND_SRC1_ALPHA;
  d.RenderTarget[0].DestBlendAlpha = BLEND_INV_SRC1_ALPHA;
  EXPECT_EQ(Validate(d), "");
}

TEST(BlendValidate, WriteMaskAboveAllIsRefusedEvenWithoutBlending) {
  BLEND_DESC d = Independent();
  d.RenderTarget[1].RenderTargetWriteMask = 0x10;
  EXPECT_EQ(Validate(d),
            "BLEND_DESC.RenderTarget[1].RenderTargetWriteMask: 0x10 has bits outside D3D11_COLOR_WRITE_ENABLE_ALL (0xF)");
  d.RenderTarget[1].RenderTargetWriteMask = 0xF;
  EXPECT_EQ(Validate(d), "");
}

TEST(BlendValidate, OnlyRenderTarget0IsCheckedWithoutIndependentBlend) {
  BLEND_DESC d;
  d.RenderTarget[1] = AlphaBlend();
  d.RenderTarget[1].SrcBlend = static_cast<BLEND>(0);
  d.RenderTarget[1].RenderTargetWriteMask = 0xFF;
  EXPECT_EQ(Validate(d), "");
  d.IndependentBlendEnable = TRUE;
  EXPECT_EQ(Validate(d), "BLEND_DESC.RenderTarget[1].SrcBlend: 0 is not a valid D3D11_BLEND");
}

TEST(BlendValidate, FactorsAreIgnoredWhileBlendingIsDisabled) {
  BLEND_DESC d;
  d.RenderTarget[0].BlendEnable = FALSE;
  d.RenderTarget[0].SrcBlend = static_cast<BLEND>(0);
  d.RenderTarget[0].DestBlendAlpha = BLEND_SRC_COLOR;
  d.RenderTarget[0].BlendOp = static_cast<BLEND_OP>(77);
  EXPECT_EQ(Validate(d), "");
}

TEST(BlendNormalize, WithoutIndependentBlendRenderTarget0FillsAllEight) {
  BLEND_DESC d;
  d.RenderTarget[0] = AlphaBlend();
  d.RenderTarget[0].RenderTargetWriteMask = COLOR_WRITE_ENABLE_RED;
  d.RenderTarget[5].BlendEnable = TRUE;
  d.RenderTarget[5].SrcBlend = BLEND_ZERO;
  const BLEND_DESC n = Normalize(d);
  for (const RENDER_TARGET_BLEND_DESC& rt : n.RenderTarget) {
    EXPECT_EQ(rt.BlendEnable, TRUE);
    EXPECT_EQ(rt.SrcBlend, BLEND_SRC_ALPHA);
    EXPECT_EQ(rt.DestBlend, BLEND_INV_SRC_ALPHA);
    EXPECT_EQ(rt.DestBlendAlpha, BLEND_INV_SRC_ALPHA);
    EXPECT_EQ(rt.RenderTargetWriteMask, COLOR_WRITE_ENABLE_RED);
  }
}

TEST(BlendNormalize, IndependentBlendKeepsEachTarget) {
  BLEND_DESC d = Independent();
  d.RenderTarget[3] = AlphaBlend();
  const BLEND_DESC n = Normalize(d);
  EXPECT_EQ(n.RenderTarget[3].SrcBlend, BLEND_SRC_ALPHA);
  EXPECT_EQ(n.RenderTarget[0].BlendEnable, FALSE);
  EXPECT_EQ(n.RenderTarget[4].BlendEnable, FALSE);
}

TEST(BlendNormalize, DisabledBlendResetsFactorsAndOps) {
  BLEND_DESC d;
  d.RenderTarget[0].SrcBlend = BLEND_DEST_COLOR;
  d.RenderTarget[0].DestBlend = BLEND_SRC1_ALPHA;
  d.RenderTarget[0].BlendOp = BLEND_OP_MIN;
  d.RenderTarget[0].SrcBlendAlpha = BLEND_ZERO;
  d.RenderTarget[0].DestBlendAlpha = BLEND_ONE;
  d.RenderTarget[0].BlendOpAlpha = BLEND_OP_MAX;
  d.RenderTarget[0].RenderTargetWriteMask = 0x3;
  const RENDER_TARGET_BLEND_DESC rt = Normalize(d).RenderTarget[0];
  EXPECT_EQ(rt.SrcBlend, BLEND_ONE);
  EXPECT_EQ(rt.DestBlend, BLEND_ZERO);
  EXPECT_EQ(rt.BlendOp, BLEND_OP_ADD);
  EXPECT_EQ(rt.SrcBlendAlpha, BLEND_ONE);
  EXPECT_EQ(rt.DestBlendAlpha, BLEND_ZERO);
  EXPECT_EQ(rt.BlendOpAlpha, BLEND_OP_ADD);
  EXPECT_EQ(rt.RenderTargetWriteMask, 0x3);  // the write mask always matters
}

TEST(BlendNormalize, BoolsBecomeZeroOrOne) {
  BLEND_DESC d;
  d.AlphaToCoverageEnable = 7;
  d.RenderTarget[0] = AlphaBlend();
  d.RenderTarget[0].BlendEnable = -1;
  const BLEND_DESC n = Normalize(d);
  EXPECT_EQ(n.AlphaToCoverageEnable, TRUE);
  EXPECT_EQ(n.IndependentBlendEnable, FALSE);
  EXPECT_EQ(n.RenderTarget[7].BlendEnable, TRUE);
}

TEST(BlendHash, EquivalentDescsShareTheKeyButNotTheRawHash) {
  BLEND_DESC a;
  a.RenderTarget[0] = AlphaBlend();
  BLEND_DESC b = a;
  b.RenderTarget[6].SrcBlend = BLEND_DEST_COLOR;  // ignored: no independent blend
  EXPECT_TRUE(KeyEqual(a, b));
  EXPECT_EQ(KeyHash(a), KeyHash(b));
  EXPECT_FALSE(RawEqual(a, b));
  EXPECT_NE(RawHash(a), RawHash(b));

  BLEND_DESC c;  // blending off: factors don't matter
  BLEND_DESC e;
  e.RenderTarget[0].SrcBlend = BLEND_SRC_ALPHA;
  e.RenderTarget[0].BlendEnable = FALSE;
  EXPECT_EQ(KeyHash(c), KeyHash(e));
  EXPECT_NE(RawHash(c), RawHash(e));
}

TEST(BlendHash, DifferentDescsDiffer) {
  BLEND_DESC a;
  a.RenderTarget[0] = AlphaBlend();
  BLEND_DESC b = a;
  b.RenderTarget[0].DestBlend = BLEND_ONE;
  EXPECT_FALSE(KeyEqual(a, b));
  EXPECT_NE(KeyHash(a), KeyHash(b));
  BLEND_DESC c = a;
  c.RenderTarget[0].RenderTargetWriteMask = 0x7;
  EXPECT_NE(KeyHash(a), KeyHash(c));
  BLEND_DESC e = a;
  e.AlphaToCoverageEnable = TRUE;
  EXPECT_NE(KeyHash(a), KeyHash(e));
}

TEST(BlendHash, PaddingIsNotHashed) {
  alignas(BLEND_DESC) unsigned char bufA[sizeof(BLEND_DESC)];
  alignas(BLEND_DESC) unsigned char bufB[sizeof(BLEND_DESC)];
  std::memset(bufA, 0xAB, sizeof(bufA));
  std::memset(bufB, 0xCD, sizeof(bufB));
  // Default-initialisation only writes the members, so the padding keeps the garbage.
  auto* a = new (bufA) BLEND_DESC;
  auto* b = new (bufB) BLEND_DESC;
  ASSERT_NE(std::memcmp(bufA, bufB, sizeof(BLEND_DESC)), 0);
  EXPECT_TRUE(RawEqual(*a, *b));
  EXPECT_EQ(RawHash(*a), RawHash(*b));
}

struct FactorCase {
  BLEND d3d;
  VkBlendFactor color;
  VkBlendFactor alpha;
};

TEST(BlendToVulkan, EveryFactor) {
  const FactorCase cases[] = {
      {BLEND_ZERO, VK_BLEND_FACTOR_ZERO, VK_BLEND_FACTOR_ZERO},
      {BLEND_ONE, VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ONE},
      {BLEND_SRC_COLOR, VK_BLEND_FACTOR_SRC_COLOR, VK_BLEND_FACTOR_SRC_COLOR},
      {BLEND_INV_SRC_COLOR, VK_BLEND_FACTOR_ONE_MINUS_SRC_COLOR, VK_BLEND_FACTOR_ONE_MINUS_SRC_COLOR},
      {BLEND_SRC_ALPHA, VK_BLEND_FACTOR_SRC_ALPHA, VK_BLEND_FACTOR_SRC_ALPHA},
      {BLEND_INV_SRC_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA},
      {BLEND_DEST_ALPHA, VK_BLEND_FACTOR_DST_ALPHA, VK_BLEND_FACTOR_DST_ALPHA},
      {BLEND_INV_DEST_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_DST_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_DST_ALPHA},
      {BLEND_DEST_COLOR, VK_BLEND_FACTOR_DST_COLOR, VK_BLEND_FACTOR_DST_COLOR},
      {BLEND_INV_DEST_COLOR, VK_BLEND_FACTOR_ONE_MINUS_DST_COLOR, VK_BLEND_FACTOR_ONE_MINUS_DST_COLOR},
      {BLEND_SRC_ALPHA_SAT, VK_BLEND_FACTOR_SRC_ALPHA_SATURATE, VK_BLEND_FACTOR_SRC_ALPHA_SATURATE},
      {BLEND_BLEND_FACTOR, VK_BLEND_FACTOR_CONSTANT_COLOR, VK_BLEND_FACTOR_CONSTANT_ALPHA},
      {BLEND_INV_BLEND_FACTOR, VK_BLEND_FACTOR_ONE_MINUS_CONSTANT_COLOR, VK_BLEND_FACTOR_ONE_MINUS_CONSTANT_ALPHA},
      {BLEND_SRC1_COLOR, VK_BLEND_FACTOR_SRC1_COLOR, VK_BLEND_FACTOR_SRC1_COLOR},
      {BLEND_INV_SRC1_COLOR, VK_BLEND_FACTOR_ONE_MINUS_SRC1_COLOR, VK_BLEND_FACTOR_ONE_MINUS_SRC1_COLOR},
      {BLEND_SRC1_ALPHA, VK_BLEND_FACTOR_SRC1_ALPHA, VK_BLEND_FACTOR_SRC1_ALPHA},
      {BLEND_INV_SRC1_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_SRC1_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_SRC1_ALPHA},
  };
  for (const FactorCase& c : cases) {
    EXPECT_EQ(ToVkBlendFactor(c.d3d, false), c.color) << BlendName(c.d3d);
    EXPECT_EQ(ToVkBlendFactor(c.d3d, true), c.alpha) << BlendName(c.d3d);
  }
}

TEST(BlendToVulkan, EveryOp) {
  EXPECT_EQ(ToVkBlendOp(BLEND_OP_ADD), VK_BLEND_OP_ADD);
  EXPECT_EQ(ToVkBlendOp(BLEND_OP_SUBTRACT), VK_BLEND_OP_SUBTRACT);
  EXPECT_EQ(ToVkBlendOp(BLEND_OP_REV_SUBTRACT), VK_BLEND_OP_REVERSE_SUBTRACT);
  EXPECT_EQ(ToVkBlendOp(BLEND_OP_MIN), VK_BLEND_OP_MIN);
  EXPECT_EQ(ToVkBlendOp(BLEND_OP_MAX), VK_BLEND_OP_MAX);
}

TEST(BlendToVulkan, WriteMask) {
  EXPECT_EQ(ToVkColorWriteMask(COLOR_WRITE_ENABLE_ALL),
            VkColorComponentFlags(VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                                  VK_COLOR_COMPONENT_A_BIT));
  EXPECT_EQ(ToVkColorWriteMask(COLOR_WRITE_ENABLE_RED | COLOR_WRITE_ENABLE_ALPHA),
            VkColorComponentFlags(VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_A_BIT));
  EXPECT_EQ(ToVkColorWriteMask(0), 0u);
}

TEST(BlendToVulkan, AlphaBlendOnAllTargets) {
  BLEND_DESC d;
  d.RenderTarget[0] = AlphaBlend();
  const BlendVk vk = ToVulkan(d);
  for (const VkPipelineColorBlendAttachmentState& a : vk.attachments) {
    EXPECT_EQ(a.blendEnable, VK_TRUE);
    EXPECT_EQ(a.srcColorBlendFactor, VK_BLEND_FACTOR_SRC_ALPHA);
    EXPECT_EQ(a.dstColorBlendFactor, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA);
    EXPECT_EQ(a.colorBlendOp, VK_BLEND_OP_ADD);
    EXPECT_EQ(a.srcAlphaBlendFactor, VK_BLEND_FACTOR_ONE);
    EXPECT_EQ(a.dstAlphaBlendFactor, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA);
    EXPECT_EQ(a.colorWriteMask, 0xFu);
  }
  EXPECT_FALSE(vk.needsIndependentBlend);
  EXPECT_FALSE(vk.usesDualSource);
  EXPECT_FALSE(vk.usesBlendConstants);
  EXPECT_EQ(vk.alphaToCoverageEnable, VK_FALSE);
}

TEST(BlendToVulkan, DisabledBlendIsCanonical) {
  BLEND_DESC d;
  d.RenderTarget[0].SrcBlend = BLEND_SRC1_COLOR;  // ignored
  const BlendVk vk = ToVulkan(d);
  EXPECT_EQ(vk.attachments[0].blendEnable, VK_FALSE);
  EXPECT_EQ(vk.attachments[0].srcColorBlendFactor, VK_BLEND_FACTOR_ONE);
  EXPECT_EQ(vk.attachments[0].dstColorBlendFactor, VK_BLEND_FACTOR_ZERO);
  EXPECT_FALSE(vk.usesDualSource);
}

TEST(BlendToVulkan, ReportsDualSourceConstantsIndependentAndAlphaToCoverage) {
  BLEND_DESC d = Independent();
  d.AlphaToCoverageEnable = TRUE;
  d.RenderTarget[0] = AlphaBlend();
  d.RenderTarget[0].DestBlend = BLEND_INV_SRC1_COLOR;
  d.RenderTarget[1] = AlphaBlend();
  d.RenderTarget[1].SrcBlendAlpha = BLEND_BLEND_FACTOR;
  const BlendVk vk = ToVulkan(d);
  EXPECT_TRUE(vk.usesDualSource);
  EXPECT_TRUE(vk.usesBlendConstants);
  EXPECT_TRUE(vk.needsIndependentBlend);
  EXPECT_EQ(vk.alphaToCoverageEnable, VK_TRUE);
  EXPECT_EQ(vk.attachments[1].srcAlphaBlendFactor, VK_BLEND_FACTOR_CONSTANT_ALPHA);
  EXPECT_EQ(vk.attachments[2].blendEnable, VK_FALSE);
}

TEST(BlendToVulkan, AdjustForMissingAlphaTreatsDestAlphaAsOne) {
  BLEND_DESC d;
  d.RenderTarget[0].BlendEnable = TRUE;
  d.RenderTarget[0].SrcBlend = BLEND_DEST_ALPHA;
  d.RenderTarget[0].DestBlend = BLEND_INV_DEST_ALPHA;
  d.RenderTarget[0].SrcBlendAlpha = BLEND_SRC_ALPHA_SAT;
  d.RenderTarget[0].DestBlendAlpha = BLEND_INV_DEST_ALPHA;
  VkPipelineColorBlendAttachmentState a = ToVulkan(d).attachments[0];
  AdjustForMissingAlpha(a);
  EXPECT_EQ(a.srcColorBlendFactor, VK_BLEND_FACTOR_ONE);
  EXPECT_EQ(a.dstColorBlendFactor, VK_BLEND_FACTOR_ZERO);
  EXPECT_EQ(a.srcAlphaBlendFactor, VK_BLEND_FACTOR_SRC_ALPHA_SATURATE);  // alpha of SAT is 1 anyway
  EXPECT_EQ(a.dstAlphaBlendFactor, VK_BLEND_FACTOR_ZERO);
  EXPECT_EQ(a.colorWriteMask, VkColorComponentFlags(VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                                    VK_COLOR_COMPONENT_B_BIT));

  VkPipelineColorBlendAttachmentState sat{};
  sat.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA_SATURATE;
  sat.dstColorBlendFactor = VK_BLEND_FACTOR_SRC_COLOR;
  AdjustForMissingAlpha(sat);
  EXPECT_EQ(sat.srcColorBlendFactor, VK_BLEND_FACTOR_ZERO);
  EXPECT_EQ(sat.dstColorBlendFactor, VK_BLEND_FACTOR_SRC_COLOR);
}

}  // namespace
}  // namespace rhi::states
