#include "fx/state_blocks.h"

#include <gtest/gtest.h>

namespace fx {
namespace {

StateValue Name(const char* s) { return StateValue{s, {}}; }
StateValue Number(std::vector<double> v) { return StateValue{"", std::move(v)}; }

TEST(StateBlocks, Fx11DefaultsDifferFromD3D11OnlyWhereFx11Does) {
  rhi::BLEND_DESC blend = DefaultBlendDesc();
  EXPECT_EQ(blend.IndependentBlendEnable, rhi::TRUE);
  EXPECT_EQ(blend.AlphaToCoverageEnable, rhi::FALSE);
  for (const auto& rt : blend.RenderTarget) {
    EXPECT_EQ(rt.BlendEnable, rhi::FALSE);
    EXPECT_EQ(rt.SrcBlend, rhi::BLEND_ONE);
    EXPECT_EQ(rt.DestBlend, rhi::BLEND_ZERO);
    EXPECT_EQ(rt.RenderTargetWriteMask, rhi::COLOR_WRITE_ENABLE_ALL);
  }
  rhi::SAMPLER_DESC sampler = DefaultSamplerDesc();
  EXPECT_EQ(sampler.Filter, rhi::FILTER_MIN_MAG_MIP_LINEAR);
  EXPECT_EQ(sampler.AddressU, rhi::TEXTURE_ADDRESS_CLAMP);
  EXPECT_EQ(sampler.MaxAnisotropy, 16u);
  EXPECT_EQ(sampler.BorderColor[0], 0.0f);
  EXPECT_EQ(sampler.BorderColor[3], 0.0f);
  EXPECT_EQ(sampler.MinLOD, -rhi::FLOAT32_MAX);
  EXPECT_EQ(sampler.MaxLOD, rhi::FLOAT32_MAX);
  rhi::DEPTH_STENCIL_DESC ds = DefaultDepthStencilDesc();
  EXPECT_EQ(ds.DepthEnable, rhi::TRUE);
  EXPECT_EQ(ds.DepthFunc, rhi::COMPARISON_LESS);
  EXPECT_EQ(ds.BackFace.StencilFunc, rhi::COMPARISON_ALWAYS);
  rhi::RASTERIZER_DESC rs = DefaultRasterizerDesc();
  EXPECT_EQ(rs.CullMode, rhi::CULL_BACK);
  EXPECT_EQ(rs.DepthClipEnable, rhi::TRUE);
}

TEST(StateBlocks, EnumSpellings) {
  rhi::BLEND_DESC d = DefaultBlendDesc();
  EXPECT_FALSE(ApplyStateAssignment(d, "SrcBlend", std::nullopt, Name("src_alpha")));
  EXPECT_EQ(d.RenderTarget[0].SrcBlend, rhi::BLEND_SRC_ALPHA);
  EXPECT_FALSE(ApplyStateAssignment(d, "destblend", 3u, Name("D3D11_BLEND_INV_SRC_ALPHA")));
  EXPECT_EQ(d.RenderTarget[3].DestBlend, rhi::BLEND_INV_SRC_ALPHA);
  EXPECT_FALSE(ApplyStateAssignment(d, "DestBlendAlpha", 1u, Name("BLEND_BLEND_FACTOR")));
  EXPECT_EQ(d.RenderTarget[1].DestBlendAlpha, rhi::BLEND_BLEND_FACTOR);
  EXPECT_FALSE(ApplyStateAssignment(d, "SrcBlendAlpha", 1u, Name("Blend_Factor")));
  EXPECT_EQ(d.RenderTarget[1].SrcBlendAlpha, rhi::BLEND_BLEND_FACTOR);
  EXPECT_FALSE(ApplyStateAssignment(d, "BlendOp", 7u, Name("d3d10_blend_op_rev_subtract")));
  EXPECT_EQ(d.RenderTarget[7].BlendOp, rhi::BLEND_OP_REV_SUBTRACT);
  EXPECT_FALSE(ApplyStateAssignment(d, "BlendEnable", 2u, Name("true")));
  EXPECT_EQ(d.RenderTarget[2].BlendEnable, rhi::TRUE);
  EXPECT_FALSE(ApplyStateAssignment(d, "BlendEnable", 2u, Number({0})));
  EXPECT_EQ(d.RenderTarget[2].BlendEnable, rhi::FALSE);
  EXPECT_FALSE(ApplyStateAssignment(d, "RenderTargetWriteMask", 5u, Number({0x3})));
  EXPECT_EQ(d.RenderTarget[5].RenderTargetWriteMask, 0x3);

  rhi::SAMPLER_DESC s = DefaultSamplerDesc();
  EXPECT_FALSE(ApplyStateAssignment(s, "Filter", std::nullopt, Number({0x55})));  // a valid enum number
  EXPECT_EQ(s.Filter, rhi::FILTER_ANISOTROPIC);
  EXPECT_FALSE(ApplyStateAssignment(s, "AddressW", std::nullopt, Name("Mirror_Once")));
  EXPECT_EQ(s.AddressW, rhi::TEXTURE_ADDRESS_MIRROR_ONCE);
  EXPECT_FALSE(ApplyStateAssignment(s, "BorderColor", std::nullopt, Number({0.25, 0.5, 0.75, 1})));
  EXPECT_EQ(s.BorderColor[2], 0.75f);
  EXPECT_FALSE(ApplyStateAssignment(s, "MaxLOD", std::nullopt, Number({3.5})));
  EXPECT_EQ(s.MaxLOD, 3.5f);

  rhi::DEPTH_STENCIL_DESC ds = DefaultDepthStencilDesc();
  EXPECT_FALSE(ApplyStateAssignment(ds, "BackFaceStencilDepthFail", std::nullopt, Name("DECR")));
  EXPECT_EQ(ds.BackFace.StencilDepthFailOp, rhi::STENCIL_OP_DECR);
  EXPECT_FALSE(ApplyStateAssignment(ds, "DepthWriteMask", std::nullopt, Name("D3D11_DEPTH_WRITE_MASK_ZERO")));
  EXPECT_EQ(ds.DepthWriteMask, rhi::DEPTH_WRITE_MASK_ZERO);

  rhi::RASTERIZER_DESC rs = DefaultRasterizerDesc();
  EXPECT_FALSE(ApplyStateAssignment(rs, "CullMode", std::nullopt, Name("D3D11_CULL_FRONT")));
  EXPECT_EQ(rs.CullMode, rhi::CULL_FRONT);
  EXPECT_FALSE(ApplyStateAssignment(rs, "DepthBias", std::nullopt, Number({-5})));
  EXPECT_EQ(rs.DepthBias, -5);
}

TEST(StateBlocks, Errors) {
  rhi::BLEND_DESC d = DefaultBlendDesc();
  auto e = ApplyStateAssignment(d, "SourceBlend", std::nullopt, Name("ONE"));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->part, StateError::Part::Member);
  EXPECT_EQ(e->message, "unknown BlendState member 'SourceBlend'");

  e = ApplyStateAssignment(d, "SrcBlend", std::nullopt, Name("LESS"));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->part, StateError::Part::Value);
  EXPECT_EQ(e->message, "invalid value 'LESS' for SrcBlend (not a blend value)");

  e = ApplyStateAssignment(d, "BlendEnable", 8u, Name("TRUE"));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->part, StateError::Part::Index);
  EXPECT_EQ(e->message, "index 8 out of range for BlendEnable (0..7)");

  e = ApplyStateAssignment(d, "AlphaToCoverageEnable", 1u, Name("TRUE"));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->part, StateError::Part::Index);

  e = ApplyStateAssignment(d, "RenderTargetWriteMask", 0u, Number({256}));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->message, "invalid value 256 for RenderTargetWriteMask (expected an integer in 0..255)");

  e = ApplyStateAssignment(d, "BlendEnable", 0u, Name("YES"));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->message, "invalid value 'YES' for BlendEnable (expected TRUE or FALSE)");

  rhi::SAMPLER_DESC s = DefaultSamplerDesc();
  e = ApplyStateAssignment(s, "BorderColor", std::nullopt, Number({1, 2}));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->message, "invalid value (1, 2) for BorderColor (expected a float4)");
  e = ApplyStateAssignment(s, "Filter", std::nullopt, Number({3}));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->message, "invalid value 3 for Filter (not a filter value)");
  e = ApplyStateAssignment(s, "IndependentBlendEnable", std::nullopt, Name("TRUE"));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->message, "unknown SamplerState member 'IndependentBlendEnable'");
  // The descs are untouched by failed assignments.
  EXPECT_EQ(s.Filter, rhi::FILTER_MIN_MAG_MIP_LINEAR);
}

}  // namespace
}  // namespace fx
