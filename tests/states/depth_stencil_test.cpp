#include "states/depth_stencil.h"

#include <gtest/gtest.h>

#include <cstring>
#include <new>

namespace rhi::states {
namespace {

DEPTH_STENCIL_DESC WithStencil() {
  DEPTH_STENCIL_DESC d;
  d.StencilEnable = TRUE;
  d.StencilReadMask = 0x0F;
  d.StencilWriteMask = 0xF0;
  d.FrontFace = {STENCIL_OP_ZERO, STENCIL_OP_INCR_SAT, STENCIL_OP_REPLACE, COMPARISON_EQUAL};
  d.BackFace = {STENCIL_OP_INVERT, STENCIL_OP_DECR, STENCIL_OP_INCR, COMPARISON_NOT_EQUAL};
  return d;
}

TEST(DepthStencilValidate, DefaultDescIsValid) { EXPECT_EQ(Validate(DEPTH_STENCIL_DESC{}), ""); }

TEST(DepthStencilValidate, DepthWriteMaskIsZeroOrAll) {
  DEPTH_STENCIL_DESC d;
  d.DepthWriteMask = static_cast<DEPTH_WRITE_MASK>(2);
  EXPECT_EQ(Validate(d), "DEPTH_STENCIL_DESC.DepthWriteMask: 2 is not a valid D3D11_DEPTH_WRITE_MASK");
  d.DepthWriteMask = DEPTH_WRITE_MASK_ZERO;
  EXPECT_EQ(Validate(d), "");
}

TEST(DepthStencilValidate, DepthFuncRange) {
  DEPTH_STENCIL_DESC d;
  d.DepthFunc = static_cast<COMPARISON_FUNC>(0);
  EXPECT_EQ(Validate(d), "DEPTH_STENCIL_DESC.DepthFunc: 0 is not a valid D3D11_COMPARISON_FUNC");
  d.DepthFunc = static_cast<COMPARISON_FUNC>(9);
  EXPECT_EQ(Validate(d), "DEPTH_STENCIL_DESC.DepthFunc: 9 is not a valid D3D11_COMPARISON_FUNC");
  d.DepthFunc = COMPARISON_GREATER_EQUAL;
  EXPECT_EQ(Validate(d), "");
}

TEST(DepthStencilValidate, DepthFieldsIgnoredWhileDepthIsDisabled) {
  DEPTH_STENCIL_DESC d;
  d.DepthEnable = FALSE;
  d.DepthWriteMask = static_cast<DEPTH_WRITE_MASK>(5);
  d.DepthFunc = static_cast<COMPARISON_FUNC>(0);
  EXPECT_EQ(Validate(d), "");
}

TEST(DepthStencilValidate, StencilOpsAndFuncs) {
  DEPTH_STENCIL_DESC d = WithStencil();
  EXPECT_EQ(Validate(d), "");
  d.FrontFace.StencilFailOp = static_cast<STENCIL_OP>(0);
  EXPECT_EQ(Validate(d), "DEPTH_STENCIL_DESC.FrontFace.StencilFailOp: 0 is not a valid D3D11_STENCIL_OP");
  d = WithStencil();
  d.FrontFace.StencilDepthFailOp = static_cast<STENCIL_OP>(9);
  EXPECT_EQ(Validate(d), "DEPTH_STENCIL_DESC.FrontFace.StencilDepthFailOp: 9 is not a valid D3D11_STENCIL_OP");
  d = WithStencil();
  d.FrontFace.StencilFunc = static_cast<COMPARISON_FUNC>(0);
  EXPECT_EQ(Validate(d), "DEPTH_STENCIL_DESC.FrontFace.StencilFunc: 0 is not a valid D3D11_COMPARISON_FUNC");
  d = WithStencil();
  d.BackFace.StencilPassOp = static_cast<STENCIL_OP>(9);
  EXPECT_EQ(Validate(d), "DEPTH_STENCIL_DESC.BackFace.StencilPassOp: 9 is not a valid D3D11_STENCIL_OP");
  d = WithStencil();
  d.BackFace.StencilFunc = static_cast<COMPARISON_FUNC>(9);
  EXPECT_EQ(Validate(d), "DEPTH_STENCIL_DESC.BackFace.StencilFunc: 9 is not a valid D3D11_COMPARISON_FUNC");
}

TEST(DepthStencilValidate, StencilFieldsIgnoredWhileStencilIsDisabled) {
  DEPTH_STENCIL_DESC d = WithStencil();
  d.StencilEnable = FALSE;
  d.BackFace.StencilPassOp = static_cast<STENCIL_OP>(9);
  EXPECT_EQ(Validate(d), "");
}

TEST(DepthStencilNormalize, DisabledDepthAndStencilResetToDefaults) {
  DEPTH_STENCIL_DESC d = WithStencil();
  d.DepthEnable = FALSE;
  d.DepthWriteMask = DEPTH_WRITE_MASK_ZERO;
  d.DepthFunc = COMPARISON_NEVER;
  d.StencilEnable = FALSE;
  const DEPTH_STENCIL_DESC n = Normalize(d);
  EXPECT_EQ(n.DepthWriteMask, DEPTH_WRITE_MASK_ALL);
  EXPECT_EQ(n.DepthFunc, COMPARISON_LESS);
  EXPECT_EQ(n.StencilReadMask, 0xFF);
  EXPECT_EQ(n.StencilWriteMask, 0xFF);
  for (const DEPTH_STENCILOP_DESC& f : {n.FrontFace, n.BackFace}) {
    EXPECT_EQ(f.StencilFailOp, STENCIL_OP_KEEP);
    EXPECT_EQ(f.StencilDepthFailOp, STENCIL_OP_KEEP);
    EXPECT_EQ(f.StencilPassOp, STENCIL_OP_KEEP);
    EXPECT_EQ(f.StencilFunc, COMPARISON_ALWAYS);
  }
}

TEST(DepthStencilNormalize, EnabledFieldsAreKeptAndBoolsCanonical) {
  DEPTH_STENCIL_DESC d = WithStencil();
  d.DepthEnable = 3;
  d.StencilEnable = 42;
  d.DepthFunc = COMPARISON_GREATER;
  const DEPTH_STENCIL_DESC n = Normalize(d);
  EXPECT_EQ(n.DepthEnable, TRUE);
  EXPECT_EQ(n.StencilEnable, TRUE);
  EXPECT_EQ(n.DepthFunc, COMPARISON_GREATER);
  EXPECT_EQ(n.StencilReadMask, 0x0F);
  EXPECT_EQ(n.BackFace.StencilFunc, COMPARISON_NOT_EQUAL);
}

TEST(DepthStencilHash, EquivalentAndDifferentDescs) {
  DEPTH_STENCIL_DESC a;  // stencil off
  DEPTH_STENCIL_DESC b = WithStencil();
  b.StencilEnable = FALSE;
  EXPECT_TRUE(KeyEqual(a, b));
  EXPECT_EQ(KeyHash(a), KeyHash(b));
  EXPECT_FALSE(RawEqual(a, b));
  EXPECT_NE(RawHash(a), RawHash(b));

  DEPTH_STENCIL_DESC c = WithStencil();
  DEPTH_STENCIL_DESC e = WithStencil();
  e.StencilWriteMask = 0xF1;
  EXPECT_NE(KeyHash(c), KeyHash(e));
  e = c;
  e.BackFace.StencilFunc = COMPARISON_LESS;
  EXPECT_NE(KeyHash(c), KeyHash(e));
  EXPECT_EQ(RawHash(c), RawHash(WithStencil()));
}

TEST(DepthStencilHash, PaddingIsNotHashed) {
  alignas(DEPTH_STENCIL_DESC) unsigned char bufA[sizeof(DEPTH_STENCIL_DESC)];
  alignas(DEPTH_STENCIL_DESC) unsigned char bufB[sizeof(DEPTH_STENCIL_DESC)];
  std::memset(bufA, 0x11, sizeof(bufA));
  std::memset(bufB, 0xEE, sizeof(bufB));
  auto* a = new (bufA) DEPTH_STENCIL_DESC;
  auto* b = new (bufB) DEPTH_STENCIL_DESC;
  ASSERT_NE(std::memcmp(bufA, bufB, sizeof(DEPTH_STENCIL_DESC)), 0);
  EXPECT_EQ(RawHash(*a), RawHash(*b));
}

TEST(DepthStencilToVulkan, CompareFuncs) {
  EXPECT_EQ(ToVkCompareOp(COMPARISON_NEVER), VK_COMPARE_OP_NEVER);
  EXPECT_EQ(ToVkCompareOp(COMPARISON_LESS), VK_COMPARE_OP_LESS);
  EXPECT_EQ(ToVkCompareOp(COMPARISON_EQUAL), VK_COMPARE_OP_EQUAL);
  EXPECT_EQ(ToVkCompareOp(COMPARISON_LESS_EQUAL), VK_COMPARE_OP_LESS_OR_EQUAL);
  EXPECT_EQ(ToVkCompareOp(COMPARISON_GREATER), VK_COMPARE_OP_GREATER);
  EXPECT_EQ(ToVkCompareOp(COMPARISON_NOT_EQUAL), VK_COMPARE_OP_NOT_EQUAL);
  EXPECT_EQ(ToVkCompareOp(COMPARISON_GREATER_EQUAL), VK_COMPARE_OP_GREATER_OR_EQUAL);
  EXPECT_EQ(ToVkCompareOp(COMPARISON_ALWAYS), VK_COMPARE_OP_ALWAYS);
}

TEST(DepthStencilToVulkan, StencilOps) {
  EXPECT_EQ(ToVkStencilOp(STENCIL_OP_KEEP), VK_STENCIL_OP_KEEP);
  EXPECT_EQ(ToVkStencilOp(STENCIL_OP_ZERO), VK_STENCIL_OP_ZERO);
  EXPECT_EQ(ToVkStencilOp(STENCIL_OP_REPLACE), VK_STENCIL_OP_REPLACE);
  EXPECT_EQ(ToVkStencilOp(STENCIL_OP_INCR_SAT), VK_STENCIL_OP_INCREMENT_AND_CLAMP);
  EXPECT_EQ(ToVkStencilOp(STENCIL_OP_DECR_SAT), VK_STENCIL_OP_DECREMENT_AND_CLAMP);
  EXPECT_EQ(ToVkStencilOp(STENCIL_OP_INVERT), VK_STENCIL_OP_INVERT);
  EXPECT_EQ(ToVkStencilOp(STENCIL_OP_INCR), VK_STENCIL_OP_INCREMENT_AND_WRAP);
  EXPECT_EQ(ToVkStencilOp(STENCIL_OP_DECR), VK_STENCIL_OP_DECREMENT_AND_WRAP);
}

TEST(DepthStencilToVulkan, DefaultDesc) {
  const VkPipelineDepthStencilStateCreateInfo vk = ToVulkan(DEPTH_STENCIL_DESC{});
  EXPECT_EQ(vk.sType, VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO);
  EXPECT_EQ(vk.pNext, nullptr);
  EXPECT_EQ(vk.depthTestEnable, VK_TRUE);
  EXPECT_EQ(vk.depthWriteEnable, VK_TRUE);
  EXPECT_EQ(vk.depthCompareOp, VK_COMPARE_OP_LESS);
  EXPECT_EQ(vk.stencilTestEnable, VK_FALSE);
  EXPECT_EQ(vk.depthBoundsTestEnable, VK_FALSE);
}

TEST(DepthStencilToVulkan, WriteMaskZeroAndDisabledDepthTurnWritesOff) {
  DEPTH_STENCIL_DESC d;
  d.DepthWriteMask = DEPTH_WRITE_MASK_ZERO;
  d.DepthFunc = COMPARISON_GREATER;
  VkPipelineDepthStencilStateCreateInfo vk = ToVulkan(d);
  EXPECT_EQ(vk.depthTestEnable, VK_TRUE);
  EXPECT_EQ(vk.depthWriteEnable, VK_FALSE);
  EXPECT_EQ(vk.depthCompareOp, VK_COMPARE_OP_GREATER);

  d.DepthEnable = FALSE;
  d.DepthWriteMask = DEPTH_WRITE_MASK_ALL;
  vk = ToVulkan(d);
  EXPECT_EQ(vk.depthTestEnable, VK_FALSE);
  EXPECT_EQ(vk.depthWriteEnable, VK_FALSE);
}

TEST(DepthStencilToVulkan, StencilFacesMasksAndDynamicReference) {
  const VkPipelineDepthStencilStateCreateInfo vk = ToVulkan(WithStencil());
  EXPECT_EQ(vk.stencilTestEnable, VK_TRUE);
  EXPECT_EQ(vk.front.failOp, VK_STENCIL_OP_ZERO);
  EXPECT_EQ(vk.front.depthFailOp, VK_STENCIL_OP_INCREMENT_AND_CLAMP);
  EXPECT_EQ(vk.front.passOp, VK_STENCIL_OP_REPLACE);
  EXPECT_EQ(vk.front.compareOp, VK_COMPARE_OP_EQUAL);
  EXPECT_EQ(vk.back.failOp, VK_STENCIL_OP_INVERT);
  EXPECT_EQ(vk.back.depthFailOp, VK_STENCIL_OP_DECREMENT_AND_WRAP);
  EXPECT_EQ(vk.back.passOp, VK_STENCIL_OP_INCREMENT_AND_WRAP);
  EXPECT_EQ(vk.back.compareOp, VK_COMPARE_OP_NOT_EQUAL);
  for (const VkStencilOpState& s : {vk.front, vk.back}) {
    EXPECT_EQ(s.compareMask, 0x0Fu);
    EXPECT_EQ(s.writeMask, 0xF0u);
    EXPECT_EQ(s.reference, 0u);
  }
}

}  // namespace
}  // namespace rhi::states
