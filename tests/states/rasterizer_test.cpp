#include "states/rasterizer.h"

#include <gtest/gtest.h>

#include <limits>

namespace rhi::states {
namespace {

TEST(RasterizerValidate, DefaultDescIsValid) { EXPECT_EQ(Validate(RASTERIZER_DESC{}), ""); }

TEST(RasterizerValidate, FillModeRange) {
  RASTERIZER_DESC d;
  d.FillMode = static_cast<FILL_MODE>(1);
  EXPECT_EQ(Validate(d), "RASTERIZER_DESC.FillMode: 1 is not a valid D3D11_FILL_MODE");
  d.FillMode = static_cast<FILL_MODE>(4);
  EXPECT_EQ(Validate(d), "RASTERIZER_DESC.FillMode: 4 is not a valid D3D11_FILL_MODE");
  d.FillMode = FILL_WIREFRAME;
  EXPECT_EQ(Validate(d), "");
}

TEST(RasterizerValidate, CullModeRange) {
  RASTERIZER_DESC d;
  d.CullMode = static_cast<CULL_MODE>(0);
  EXPECT_EQ(Validate(d), "RASTERIZER_DESC.CullMode: 0 is not a valid D3D11_CULL_MODE");
  d.CullMode = static_cast<CULL_MODE>(4);
  EXPECT_EQ(Validate(d), "RASTERIZER_DESC.CullMode: 4 is not a valid D3D11_CULL_MODE");
  d.CullMode = CULL_NONE;
  EXPECT_EQ(Validate(d), "");
}

TEST(RasterizerValidate, BiasFloatsMustBeFinite) {
  RASTERIZER_DESC d;
  d.DepthBiasClamp = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(Validate(d), "RASTERIZER_DESC.DepthBiasClamp: NaN is not a finite number");
  d.DepthBiasClamp = 0.5f;
  d.SlopeScaledDepthBias = std::numeric_limits<float>::infinity();
  EXPECT_EQ(Validate(d), "RASTERIZER_DESC.SlopeScaledDepthBias: +INF is not a finite number");
  d.SlopeScaledDepthBias = -std::numeric_limits<float>::infinity();
  EXPECT_EQ(Validate(d), "RASTERIZER_DESC.SlopeScaledDepthBias: -INF is not a finite number");
  d.SlopeScaledDepthBias = -2.0f;
  EXPECT_EQ(Validate(d), "");
}

TEST(RasterizerNormalize, OnlyBoolsChange) {
  RASTERIZER_DESC d;
  d.FrontCounterClockwise = 9;
  d.DepthClipEnable = 2;
  d.ScissorEnable = -1;
  d.DepthBias = 7;
  d.DepthBiasClamp = 0.25f;
  const RASTERIZER_DESC n = Normalize(d);
  EXPECT_EQ(n.FrontCounterClockwise, TRUE);
  EXPECT_EQ(n.DepthClipEnable, TRUE);
  EXPECT_EQ(n.ScissorEnable, TRUE);
  EXPECT_EQ(n.MultisampleEnable, FALSE);
  EXPECT_EQ(n.DepthBias, 7);
  EXPECT_EQ(n.DepthBiasClamp, 0.25f);
}

TEST(RasterizerHash, EquivalentAndDifferentDescs) {
  RASTERIZER_DESC a;
  RASTERIZER_DESC b;
  b.DepthClipEnable = 5;  // still TRUE
  EXPECT_TRUE(KeyEqual(a, b));
  EXPECT_EQ(KeyHash(a), KeyHash(b));
  EXPECT_FALSE(RawEqual(a, b));
  EXPECT_NE(RawHash(a), RawHash(b));

  RASTERIZER_DESC c;
  c.CullMode = CULL_FRONT;
  EXPECT_NE(KeyHash(a), KeyHash(c));
  RASTERIZER_DESC e;
  e.SlopeScaledDepthBias = 1.0f;
  EXPECT_NE(KeyHash(a), KeyHash(e));
  EXPECT_FALSE(KeyEqual(a, e));
}

TEST(RasterizerToVulkan, FillCullAndFrontFace) {
  EXPECT_EQ(ToVkPolygonMode(FILL_SOLID), VK_POLYGON_MODE_FILL);
  EXPECT_EQ(ToVkPolygonMode(FILL_WIREFRAME), VK_POLYGON_MODE_LINE);
  EXPECT_EQ(ToVkCullMode(CULL_NONE), VkCullModeFlags(VK_CULL_MODE_NONE));
  EXPECT_EQ(ToVkCullMode(CULL_FRONT), VkCullModeFlags(VK_CULL_MODE_FRONT_BIT));
  EXPECT_EQ(ToVkCullMode(CULL_BACK), VkCullModeFlags(VK_CULL_MODE_BACK_BIT));
  // Negative-height viewport: framebuffer winding == D3D winding, no swap.
  EXPECT_EQ(ToVkFrontFace(FALSE), VK_FRONT_FACE_CLOCKWISE);
  EXPECT_EQ(ToVkFrontFace(TRUE), VK_FRONT_FACE_COUNTER_CLOCKWISE);
}

TEST(RasterizerToVulkan, DefaultDesc) {
  const RasterizerVk vk = ToVulkan(RASTERIZER_DESC{}, true);
  EXPECT_EQ(vk.info.sType, VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
  EXPECT_EQ(vk.info.pNext, nullptr);
  EXPECT_EQ(vk.info.polygonMode, VK_POLYGON_MODE_FILL);
  EXPECT_EQ(vk.info.cullMode, VkCullModeFlags(VK_CULL_MODE_BACK_BIT));
  EXPECT_EQ(vk.info.frontFace, VK_FRONT_FACE_CLOCKWISE);
  EXPECT_EQ(vk.info.depthBiasEnable, VK_FALSE);
  EXPECT_EQ(vk.info.lineWidth, 1.0f);
  EXPECT_FALSE(vk.scissorEnable);
  EXPECT_FALSE(vk.needsFillModeNonSolid);
  EXPECT_FALSE(vk.needsDepthBiasClamp);
}

TEST(RasterizerToVulkan, DepthClipWithExtension) {
  RASTERIZER_DESC d;
  RasterizerVk vk = ToVulkan(d, true);
  EXPECT_TRUE(vk.usesDepthClipExt);
  EXPECT_EQ(vk.info.depthClampEnable, VK_TRUE);  // D3D always clamps to the viewport depth range
  EXPECT_EQ(vk.depthClip.sType, VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_DEPTH_CLIP_STATE_CREATE_INFO_EXT);
  EXPECT_EQ(vk.depthClip.depthClipEnable, VK_TRUE);
  EXPECT_TRUE(vk.needsDepthClampFeature);
  d.DepthClipEnable = FALSE;
  vk = ToVulkan(d, true);
  EXPECT_EQ(vk.depthClip.depthClipEnable, VK_FALSE);
  EXPECT_EQ(vk.info.depthClampEnable, VK_TRUE);
}

TEST(RasterizerToVulkan, DepthClipWithoutExtension) {
  RASTERIZER_DESC d;
  RasterizerVk vk = ToVulkan(d, false);
  EXPECT_FALSE(vk.usesDepthClipExt);
  EXPECT_EQ(vk.info.depthClampEnable, VK_FALSE);
  EXPECT_FALSE(vk.needsDepthClampFeature);
  d.DepthClipEnable = FALSE;
  vk = ToVulkan(d, false);
  EXPECT_EQ(vk.info.depthClampEnable, VK_TRUE);
  EXPECT_TRUE(vk.needsDepthClampFeature);
}

TEST(RasterizerToVulkan, DepthBias) {
  RASTERIZER_DESC d;
  d.DepthBiasClamp = 0.5f;  // alone it does nothing
  EXPECT_EQ(ToVulkan(d, true).info.depthBiasEnable, VK_FALSE);
  d.DepthBias = -100;
  d.SlopeScaledDepthBias = 2.5f;
  const RasterizerVk vk = ToVulkan(d, true);
  EXPECT_EQ(vk.info.depthBiasEnable, VK_TRUE);
  EXPECT_EQ(vk.info.depthBiasConstantFactor, -100.0f);
  EXPECT_EQ(vk.info.depthBiasSlopeFactor, 2.5f);
  EXPECT_EQ(vk.info.depthBiasClamp, 0.5f);
  EXPECT_TRUE(vk.needsDepthBiasClamp);
}

TEST(RasterizerToVulkan, ScissorAndWireframe) {
  RASTERIZER_DESC d;
  d.ScissorEnable = TRUE;
  d.FillMode = FILL_WIREFRAME;
  d.CullMode = CULL_NONE;
  d.FrontCounterClockwise = TRUE;
  const RasterizerVk vk = ToVulkan(d, true);
  EXPECT_TRUE(vk.scissorEnable);
  EXPECT_TRUE(vk.needsFillModeNonSolid);
  EXPECT_EQ(vk.info.polygonMode, VK_POLYGON_MODE_LINE);
  EXPECT_EQ(vk.info.cullMode, VkCullModeFlags(VK_CULL_MODE_NONE));
  EXPECT_EQ(vk.info.frontFace, VK_FRONT_FACE_COUNTER_CLOCKWISE);
}

TEST(RasterizerToVulkan, LineRasterizationTable) {
  RASTERIZER_DESC d;
  EXPECT_EQ(ToVkLineMode(d), VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT);
  d.AntialiasedLineEnable = TRUE;
  EXPECT_EQ(ToVkLineMode(d), VK_LINE_RASTERIZATION_MODE_RECTANGULAR_SMOOTH_EXT);
  d.MultisampleEnable = TRUE;
  EXPECT_EQ(ToVkLineMode(d), VK_LINE_RASTERIZATION_MODE_RECTANGULAR_EXT);
  d.AntialiasedLineEnable = FALSE;
  EXPECT_EQ(ToVkLineMode(d), VK_LINE_RASTERIZATION_MODE_RECTANGULAR_EXT);
  const RasterizerVk vk = ToVulkan(d, true);
  EXPECT_EQ(vk.line.sType, VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_LINE_STATE_CREATE_INFO_EXT);
  EXPECT_EQ(vk.line.lineRasterizationMode, VK_LINE_RASTERIZATION_MODE_RECTANGULAR_EXT);
  EXPECT_EQ(vk.line.stippledLineEnable, VK_FALSE);
}

}  // namespace
}  // namespace rhi::states
